// The scene's camera from its glTF camera node: glTF cameras look along their
// node's −Z with +Y up (glTF 2.0 §3.10).
#include "src/formats/gltf_camera.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rsl {

static bool node_is_animated(const Scene& scene, int node) {
    for (int n = node; n >= 0; n = scene.nodes[n].parent)
        if (scene.nodes[n].translation || scene.nodes[n].rotation || scene.nodes[n].scale) return true;
    return false;
}

// The glTF camera's pose: its node's origin, looking along −Z with +Y up;
// the target lies ahead at the distance of the scene's centre (where an
// orbiting viewer turns). An animated node gives keyed paths sampled at
// the animation's frame rate; the up vector keeps its value at the start.
void use_gltf_camera(Scene& scene, const Bounds& bounds) {
    GltfCamera& gltf = *scene.gltf_camera;
    gltf.used = true;
    Camera& camera = scene.camera;
    const auto pose = [&](float t) {
        const Mat4 m = scene.node_world_at(gltf.node, t);
        const Vec3 position(m[3]);
        const Vec3 forward = glm::normalize(Mat3(m) * Vec3(0, 0, -1));
        const float distance = bounds.empty() ? 1.0f : std::max(glm::length(bounds.center() - position), 1e-3f);
        return std::pair{position, position + distance * forward};
    };
    std::tie(camera.position, camera.target) = pose(scene.animation.start);
    camera.up = glm::normalize(Mat3(scene.node_world_at(gltf.node, scene.animation.start)) * Vec3(0, 1, 0));
    camera.fov_y_degrees = gltf.fov_y_degrees;
    const float span = scene.animation.end - scene.animation.start;
    if (!node_is_animated(scene, gltf.node) || !(span > 0)) return;
    const int frames = std::clamp(int(std::ceil(span * scene.animation.fps)), 1, 100000);
    Vec3Track positions, targets;
    for (int f = 0; f <= frames; ++f) {
        const float t = scene.animation.start + span * float(f) / float(frames);
        const auto [position, target] = pose(t);
        positions.times.push_back(t), targets.times.push_back(t);
        positions.values.push_back(position), targets.values.push_back(target);
    }
    camera.position_path = std::move(positions);
    camera.target_path = std::move(targets);
}

}  // namespace rsl
