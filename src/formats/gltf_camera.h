#pragma once
// The scene's camera from its glTF camera node (docs/SCENE_FORMAT.md, "glTF files").
#include "src/core/mesh.h"
#include "src/core/scene.h"

namespace rsl {

// Sets scene.camera's pose and field of view from scene.gltf_camera (which
// must be set) at animation.start, with keyed paths when the node is
// animated; `bounds` are the scene's world bounds at the start. Marks the
// glTF camera used. The size (width, height) is left as it is.
void use_gltf_camera(Scene& scene, const Bounds& bounds);

}  // namespace rsl
