#pragma once
// Internal to the glTF loader: a file's skins become scene skins
// (src/core/skinning.h), their joints scene nodes.
#include <filesystem>

#include "src/formats/gltf_accessor_reader.h"
#include "src/formats/gltf_model.h"
#include "src/core/scene.h"

namespace rsl::gltf {

// Appends the file's skin `skin_index` to scene.skins and returns its index
// there. Throws rsl::Error naming the file when an index is out of range, a
// joint is not in the default scene, or the inverse bind matrices are not
// one MAT4 per joint (absent: identities, as glTF specifies).
int import_skin(const tinygltf::Model& model, const std::filesystem::path& path, const AccessorReader& reader,
                const SceneNodes& nodes, int skin_index, Scene& scene);

}  // namespace rsl::gltf
