#include "tools/assets/skinned_tube.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "tools/assets/primitives.h"

namespace rsl::assets {

GeneratedModel make_bending_tube(const TubeOptions& options) {
    GeneratedModel model;
    model.scene.name = options.name;
    model.loop_seconds = options.period;
    model.animation_name = "bend";
    add_bending_tube(model, options);
    return model;
}

void add_bending_tube(GeneratedModel& model, const TubeOptions& o) {
    const float step = o.length / float(o.joints);
    GeneratedSkin skin;
    skin.name = o.name;
    for (int k = 0; k < o.joints; ++k) {
        const int parent = k == 0 ? -1 : skin.joint_nodes.back();
        const Vec3 at = k == 0 ? o.position : Vec3(0, step, 0);
        skin.joint_nodes.push_back(model.add_node(fmt::format("{}_joint{}", o.name, k), parent, at));
        skin.inverse_bind.push_back(glm::translate(Mat4(1.0f), Vec3(0, -step * float(k), 0)));
    }
    constexpr int kKeys = 24;  // even: a key at half the period (the full bend)
    const float T = o.period;
    const auto bend = [=](float t) { return 0.5f - 0.5f * std::cos(2.0f * kPi * t / T); };
    SceneNode& root = model.scene.nodes[size_t(skin.joint_nodes[0])];
    if (o.turn_degrees != 0)
        root.rotation = loop_rotation_track(
            [=](float t) { return glm::angleAxis(glm::radians(o.turn_degrees) * std::sin(2.0f * kPi * t / T), Vec3(0, 1, 0)); },
            T, kKeys);
    const float per_joint = glm::radians(o.bend_degrees) / float(std::max(1, o.joints - 1));
    for (int k = 1; k < o.joints; ++k)
        model.scene.nodes[size_t(skin.joint_nodes[size_t(k)])].rotation =
            loop_rotation_track([=](float t) { return glm::angleAxis(per_joint * bend(t), Vec3(0, 0, 1)); }, T, kKeys);

    TriangleMesh mesh = capsule(o.radius, 0.5f * o.length - o.radius, o.spacing);
    transform_mesh(mesh, translate_rotate(Vec3(0, 0.5f * o.length, 0)));
    set_axis_tangents(mesh);
    mesh.name = o.name;
    for (const Vec3& p : mesh.positions) {
        const float y = p.y;
        const int segment = std::clamp(int(std::floor(y / step)), 0, o.joints - 1);
        // The nearest joint above the first, and the ramp across it.
        const int k = std::clamp(int(std::lround(y / step)), 1, std::max(1, o.joints - 1));
        const float x = (y - step * float(k) + o.blend) / (2.0f * o.blend);
        JointIndices joints{uint16_t(segment)};
        JointWeights weights{1.0f};
        if (o.joints > 1 && x > 0 && x < 1) {
            const float s = x * x * (3 - 2 * x);
            joints = {uint16_t(k), uint16_t(k - 1)};
            weights = {s, 1 - s};
        }
        skin.joints.push_back(joints);
        skin.weights.push_back(weights);
    }
    skin.mesh = std::move(mesh);
    model.skins.push_back(std::move(skin));
}

TubeOptions demo_tube_options() {
    TubeOptions o;
    o.radius = 0.12f;
    o.length = 1.2f;
    o.joints = 3;
    o.spacing = 0.015f;
    o.blend = 0.08f;
    o.bend_degrees = 100;
    o.period = 4;
    o.turn_degrees = 40;
    return o;
}

}  // namespace rsl::assets
