#include "tools/assets/walker.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "tools/assets/pbr_scene.h"
#include "tools/assets/primitives.h"

namespace rsl::assets {

namespace {

// The figure in its bind pose: standing on y = 0, facing +x, the hips' joint
// at (0, kHipHeight, 0).
constexpr float kHipHeight = 0.9f, kKnee = 0.46f, kHipSide = 0.1f, kLegRadius = 0.075f;
constexpr float kTorsoRadius = 0.17f, kTorsoBottom = 0.85f, kTorsoTop = 1.45f, kHeadRadius = 0.12f, kHeadY = 1.6f;
constexpr float kShoulderY = 1.38f, kShoulderSide = 0.26f, kArmRadius = 0.05f, kArmLength = 0.62f;
constexpr int kAtlas = 64;

enum Joint : uint16_t { kHips, kSpine, kThighL, kShinL, kThighR, kShinR, kArmL, kArmR, kJoints };

float smoothstep(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3 - 2 * x);
}

// Texture coordinate u around a vertical axis through (x, z).
float around(const Vec3& p, float x, float z) {
    return 0.5f + std::atan2(p.z - z, p.x - x) / (2.0f * kPi);
}

// The region of the atlas a texel row belongs to, by v.
Color base_color_at(int i, int j) {
    const float v = (float(j) + 0.5f) / kAtlas;
    if (v < 0.25f) return (i % 16 == 0) ? Color(0.3f, 0.25f, 0.15f) : Color(0.1f, 0.16f, 0.32f);  // denim, seams
    if (v < 0.5f) return Color(0.78f, 0.56f, 0.45f);                                             // skin
    const float torso = (v - 0.5f) / 0.5f;  // 0 at the torso's bottom, 1 at the head's top
    if (torso < 0.08f) return Color(0.25f, 0.15f, 0.08f);                                        // belt
    if (torso < 0.1f) return Color(0.8f, 0.7f, 0.3f);                                            // buckle band
    if (torso > 0.72f) return Color(0.78f, 0.56f, 0.45f);                                        // head
    return (j / 3) % 2 == 0 ? Color(0.75f, 0.2f, 0.1f) : Color(0.9f, 0.85f, 0.75f);              // striped shirt
}

Vec2 metallic_roughness_at(int j) {
    const float v = (float(j) + 0.5f) / kAtlas;
    if (v < 0.25f) return Vec2(0.9f, 0.0f);
    if (v < 0.5f) return Vec2(0.5f, 0.0f);
    const float torso = (v - 0.5f) / 0.5f;
    if (torso < 0.08f) return Vec2(0.45f, 0.0f);
    if (torso < 0.1f) return Vec2(0.3f, 1.0f);
    if (torso > 0.72f) return Vec2(0.5f, 0.0f);
    return Vec2(0.65f, 0.0f);
}

// Adds a capsule along +Y from y0 to y1 at (x, z), each vertex weighted by
// `weigh` and given texture coordinates from `uv`.
template <typename Weigh, typename Uv>
void add_limb(TriangleMesh& mesh, GeneratedSkin& skin, float radius, float y0, float y1, float x, float z,
              float spacing, Weigh&& weigh, Uv&& uv) {
    TriangleMesh limb = capsule(radius, 0.5f * (y1 - y0) - radius, spacing);
    transform_mesh(limb, translate_rotate(Vec3(x, 0.5f * (y0 + y1), z)));
    set_axis_tangents(limb);
    for (const Vec3& p : limb.positions) {
        JointIndices joints{};
        JointWeights weights{};
        weigh(p, joints, weights);
        skin.joints.push_back(joints);
        skin.weights.push_back(weights);
        limb.texcoords.push_back(uv(p));
    }
    append_mesh(mesh, limb);
}

// Two joints blended by a smoothstep across y = at ± half_width (upper above).
auto blend_across(uint16_t lower, uint16_t upper, float at, float half_width) {
    return [=](const Vec3& p, JointIndices& joints, JointWeights& weights) {
        const float s = smoothstep((p.y - at + half_width) / (2 * half_width));
        if (s >= 1.0f) joints = {upper}, weights = {1.0f};
        else if (s <= 0.0f) joints = {lower}, weights = {1.0f};
        else if (s >= 0.5f) joints = {upper, lower}, weights = {s, 1 - s};
        else joints = {lower, upper}, weights = {1 - s, s};
    };
}

}  // namespace

std::shared_ptr<Texture> walker_base_color_texture() {
    auto t = std::make_shared<Texture>();
    t->name = "walker_base_color.png";
    t->image = Image(kAtlas, kAtlas, 3);
    for (int j = 0; j < kAtlas; ++j)
        for (int i = 0; i < kAtlas; ++i) t->image.set_rgb(i, j, base_color_at(i, j));
    return t;
}

std::shared_ptr<Texture> walker_metallic_roughness_texture() {
    auto t = std::make_shared<Texture>();
    t->name = "walker_metallic_roughness.png";
    t->image = Image(kAtlas, kAtlas, 3);
    for (int j = 0; j < kAtlas; ++j)
        for (int i = 0; i < kAtlas; ++i) {
            const Vec2 rm = metallic_roughness_at(j);
            t->image.set_rgb(i, j, Color(1.0f, rm.x, rm.y));
        }
    return t;
}

MaterialDesc walker_material() {
    MaterialDesc m = gltf_pbr_material("walker", Color(1.0f), 1.0f, 1.0f);
    m.base_color_texture = walker_base_color_texture();
    m.metallic_roughness_texture = walker_metallic_roughness_texture();
    return m;
}

GeneratedModel make_walker(const WalkerOptions& o) {
    GeneratedModel model;
    model.scene.name = o.name;
    model.loop_seconds = o.period;
    model.animation_name = "walk";
    model.scene.materials = {walker_material()};

    // The skeleton: joint nodes and their bind positions.
    GeneratedSkin skin;
    skin.name = o.name;
    skin.material = 0;
    const char* names[kJoints] = {"hips", "spine", "thigh_l", "shin_l", "thigh_r", "shin_r", "arm_l", "arm_r"};
    const int parents[kJoints] = {-1, kHips, kHips, kThighL, kHips, kThighR, kSpine, kSpine};
    const Vec3 bind[kJoints] = {{0, kHipHeight, 0},         {0, kHipHeight + 0.15f, 0},
                                {0, kHipHeight, kHipSide},  {0, kKnee, kHipSide},
                                {0, kHipHeight, -kHipSide}, {0, kKnee, -kHipSide},
                                {0, kShoulderY, kShoulderSide}, {0, kShoulderY, -kShoulderSide}};
    for (int j = 0; j < kJoints; ++j) {
        const Vec3 local = parents[j] < 0 ? bind[j] : bind[j] - bind[parents[j]];
        skin.joint_nodes.push_back(model.add_node(fmt::format("{}_{}", o.name, names[j]),
                                                  parents[j] < 0 ? -1 : skin.joint_nodes[size_t(parents[j])], local));
        skin.inverse_bind.push_back(glm::translate(Mat4(1.0f), -bind[j]));
    }

    // The mesh: torso and head (hips below the waist, spine above), legs
    // (thigh above the knee, shin below), arms (rigid on their joints).
    TriangleMesh mesh;
    const float torso_span = (kHeadY + kHeadRadius) - kTorsoBottom;
    const auto torso_uv = [&](const Vec3& p) {
        return Vec2(around(p, 0, 0), 0.5f + 0.5f * std::clamp((p.y - kTorsoBottom) / torso_span, 0.0f, 0.999f));
    };
    add_limb(mesh, skin, kTorsoRadius, kTorsoBottom, kTorsoTop, 0, 0, o.spacing,
             blend_across(kHips, kSpine, 1.02f, 0.06f), torso_uv);
    {
        TriangleMesh head = sphere(kHeadRadius, o.spacing);
        transform_mesh(head, translate_rotate(Vec3(0, kHeadY, 0)));
        set_axis_tangents(head);
        for (const Vec3& p : head.positions) {
            skin.joints.push_back(JointIndices{kSpine});
            skin.weights.push_back(JointWeights{1.0f});
            head.texcoords.push_back(torso_uv(p));
        }
        append_mesh(mesh, head);
    }
    for (const float side : {kHipSide, -kHipSide}) {
        const uint16_t thigh = side > 0 ? kThighL : kThighR, shin = side > 0 ? kShinL : kShinR;
        add_limb(mesh, skin, kLegRadius, 0.0f, kHipHeight, 0, side, o.spacing,
                 blend_across(shin, thigh, kKnee, 0.06f), [&](const Vec3& p) {
                     return Vec2(around(p, 0, side), 0.25f * std::clamp(p.y / kHipHeight, 0.0f, 0.999f));
                 });
    }
    for (const float side : {kShoulderSide, -kShoulderSide}) {
        const uint16_t arm = side > 0 ? kArmL : kArmR;
        add_limb(mesh, skin, kArmRadius, kShoulderY - kArmLength, kShoulderY + kArmRadius, 0, side, o.spacing,
                 [&](const Vec3&, JointIndices& joints, JointWeights& weights) { joints = {arm}, weights = {1.0f}; },
                 [&](const Vec3& p) {
                     return Vec2(around(p, 0, side),
                                 0.25f + 0.25f * std::clamp((p.y - (kShoulderY - kArmLength)) / (kArmLength + kArmRadius),
                                                            0.0f, 0.999f));
                 });
    }
    mesh.name = o.name;
    skin.mesh = std::move(mesh);

    // The walk: the hips round the circle facing their way with a small bob,
    // the legs swinging and the knees bending, the arms swinging against them.
    constexpr int kKeys = 96;
    const float T = o.period;
    const float steps = float(o.steps_per_lap);
    const auto lap = [=](float t) { return 2.0f * kPi * t / T; };
    const auto gait = [=](float t) { return 2.0f * kPi * steps * t / T; };
    SceneNode& hips = model.scene.nodes[size_t(skin.joint_nodes[kHips])];
    hips.translation = loop_translation_track([=](float t) {
        return Vec3(o.circle_radius * std::cos(lap(t)), kHipHeight + 0.02f * std::cos(2.0f * gait(t)),
                    o.circle_radius * std::sin(lap(t)));
    }, T, kKeys);
    // Facing the direction of travel (−sin θ, 0, cos θ): a turn of −θ − π/2 about +Y.
    hips.rotation = loop_rotation_track(
        [=](float t) { return glm::angleAxis(-lap(t) - 0.5f * kPi, Vec3(0, 1, 0)); }, T, kKeys);
    const auto swing = [&](uint16_t joint, auto&& degrees) {
        model.scene.nodes[size_t(skin.joint_nodes[joint])].rotation = loop_rotation_track(
            [=](float t) { return glm::angleAxis(glm::radians(degrees(t)), Vec3(0, 0, 1)); }, T, kKeys);
    };
    swing(kThighL, [=](float t) { return 25.0f * std::sin(gait(t)); });
    swing(kThighR, [=](float t) { return -25.0f * std::sin(gait(t)); });
    swing(kShinL, [=](float t) { return -35.0f * (0.5f - 0.5f * std::cos(gait(t))); });
    swing(kShinR, [=](float t) { return -35.0f * (0.5f + 0.5f * std::cos(gait(t))); });
    swing(kArmL, [=](float t) { return -20.0f * std::sin(gait(t)); });
    swing(kArmR, [=](float t) { return 20.0f * std::sin(gait(t)); });
    model.skins.push_back(std::move(skin));
    return model;
}

}  // namespace rsl::assets
