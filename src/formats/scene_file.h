#pragma once
// The scene file (docs/SCENE_FORMAT.md): JSON naming meshes, glTF files,
// materials, lights, the environment and the animation, read into the Scene
// of src/core/scene.h.
#include <filesystem>

#include "src/core/scene.h"

namespace rsl {

// Loads a JSON scene file, a .gltf/.glb (one part per mesh node, node
// animation), or a single .obj (one part). Throws rsl::Error naming the file.
Scene load_scene(const std::filesystem::path& path);

}  // namespace rsl
