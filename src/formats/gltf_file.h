#pragma once
// glTF 2.0 files (.gltf, .glb) as a scene's parts (docs/SCENE_FORMAT.md,
// "glTF files"). The reader is tinygltf, configured once in gltf_model.h.
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/scene.h"

namespace rsl {

// Parts, nodes, animation, lights and camera of a glTF file's default scene,
// appended to `scene`. Its materials become scene materials (Convert), or
// every part takes default_material (Override: a scene file's
// `part_materials["*"]`, docs/SCENE_FORMAT.md).
// `animations`: the names of the animations that play (a scene file's
// `gltf_animations`; "#i" for an unnamed one); empty: every animation.
enum class GltfMaterialUse { Convert, Override };
void load_gltf_into(const std::filesystem::path& path, Scene& scene, int default_material,
                    GltfMaterialUse use = GltfMaterialUse::Convert, const std::vector<std::string>& animations = {});

// How rsl treats a glTF extension: "honoured", "ignored: …" (the file still
// renders, without what the extension adds) or "not supported: …"; a file
// that requires an extension rsl does not honour is refused.
std::string gltf_extension_support(const std::string& name);
bool gltf_extension_honoured(const std::string& name);

}  // namespace rsl
