#pragma once
// tinygltf as rsl includes it: every file that includes tiny_gltf.h must set
// the same TINYGLTF_NO_* macros (they change inline defaults), so they are
// set here, once. The implementation lives in src/formats/gltf_loader.cpp.
// tinygltf's own stb is left out: src/formats/gltf_materials.cpp decodes base
// colour images with Debian's stb_image (compiled once, in rsl_formats).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include <filesystem>
#include <vector>

#include "src/core/scene.h"

namespace rsl::gltf {

// The default scene's nodes: `order` lists the file's node indices
// depth-first from the scene's roots; `scene_node[n]` is file node n's index
// in the rsl::Scene, or -1 when n is not in the default scene.
struct SceneNodes {
    std::vector<int> order;
    std::vector<int> scene_node;
};

// Throws when the file requires an extension rsl does not honour.
void check_required_extensions(const tinygltf::Model& model, const std::filesystem::path& path);
// KHR_lights_punctual point and spot lights on the default scene's nodes
// become sphere lights, directional lights suns (EnvironmentDesc::suns).
void import_lights(const tinygltf::Model& model, const std::filesystem::path& path, const SceneNodes& nodes,
                   Scene& scene);
// The first perspective camera node of the default scene, when the scene has
// no glTF camera yet.
void import_camera(const tinygltf::Model& model, const std::filesystem::path& path, const SceneNodes& nodes,
                   Scene& scene);

}  // namespace rsl::gltf
