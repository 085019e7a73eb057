#include "tools/assets/robot.h"

#include <algorithm>
#include <cmath>

#include "tools/assets/primitives.h"

namespace rsl::assets {
namespace {

// Vertex spacing (m) per part, tuned so the 12 parts total ~60k vertices
// with smaller parts denser (a hand still resolves the shadows it receives).
constexpr float kTorsoSpacing = 0.0100f;
constexpr float kHeadSpacing = 0.0075f;
constexpr float kArmSpacing = 0.0068f;
constexpr float kHandSpacing = 0.0045f;
constexpr float kLegSpacing = 0.0085f;

// Body dimensions (m).
constexpr float kHipWidth = 0.10f;       // hip joint offset from the centre line
constexpr float kThighLength = 0.42f;
constexpr float kShinLength = 0.42f;
constexpr float kUpperArmLength = 0.28f;
constexpr float kForearmLength = 0.25f;
constexpr float kShoulderWidth = 0.27f;
constexpr float kFootBelowAnkle = 0.08f;  // ankle to sole
constexpr float kAnkleRadius = 0.045f;
// The foot: a rounded box under the ankle, toes forward (+Z), in the shin's frame.
constexpr Vec3 kFootHalfExtents(0.055f, 0.04f, 0.12f);
constexpr float kFootRounding = 0.035f;
constexpr Vec3 kFootCenter(0, -kShinLength - (kFootBelowAnkle - 0.04f), 0.05f);

float radians(float degrees) { return degrees * kPi / 180.0f; }
Quat about(Vec3 axis, float degrees) { return glm::angleAxis(radians(degrees), axis); }
const Vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

// A limb segment hanging from its joint at the origin down to y = −length.
TriangleMesh hanging_limb(float r_joint, float r_end, float length, float spacing) {
    TriangleMesh limb = round_cone(r_end, r_joint, length, spacing);
    transform_mesh(limb, translate_rotate(Vec3(0, -length, 0)));
    return limb;
}

TriangleMesh placed(TriangleMesh mesh, Vec3 at, Vec3 axis = kY, float radians_ = 0) {
    transform_mesh(mesh, translate_rotate(at, axis, radians_));
    return mesh;
}

TriangleMesh torso_mesh() {
    TriangleMesh m = rounded_box(Vec3(0.15f, 0.07f, 0.10f), 0.05f, kTorsoSpacing);  // pelvis
    transform_mesh(m, translate_rotate(Vec3(0, 0.02f, 0)));
    append_mesh(m, placed(round_cone(0.10f, 0.13f, 0.18f, kTorsoSpacing), Vec3(0, 0.05f, 0)));  // waist
    append_mesh(m, placed(rounded_box(Vec3(0.20f, 0.16f, 0.12f), 0.07f, kTorsoSpacing), Vec3(0, 0.36f, 0)));  // chest
    append_mesh(m, placed(sphere(0.045f, kTorsoSpacing), Vec3(0, 0.36f, 0.12f)));  // chest light
    return m;
}

TriangleMesh head_mesh() {
    TriangleMesh m = capsule(0.045f, 0.05f, kHeadSpacing);  // neck
    transform_mesh(m, translate_rotate(Vec3(0, 0.04f, 0)));
    append_mesh(m, placed(rounded_box(Vec3(0.10f, 0.11f, 0.11f), 0.07f, kHeadSpacing), Vec3(0, 0.18f, 0.01f)));
    // Visor across the face and two ear discs make the facing readable.
    append_mesh(m, placed(capsule(0.028f, 0.06f, kHeadSpacing), Vec3(0, 0.20f, 0.105f), kZ, kPi / 2));
    for (float side : {-1.0f, 1.0f}) append_mesh(m, placed(sphere(0.035f, kHeadSpacing), Vec3(side * 0.10f, 0.18f, 0.0f)));
    return m;
}

TriangleMesh upper_arm_mesh() {
    TriangleMesh m = sphere(0.072f, kArmSpacing);  // shoulder
    append_mesh(m, hanging_limb(0.06f, 0.05f, kUpperArmLength, kArmSpacing));
    return m;
}

TriangleMesh forearm_mesh() { return hanging_limb(0.05f, 0.04f, kForearmLength, kArmSpacing); }

TriangleMesh hand_mesh() {
    TriangleMesh m = rounded_box(Vec3(0.028f, 0.06f, 0.045f), 0.022f, kHandSpacing);  // palm and fingers
    transform_mesh(m, translate_rotate(Vec3(0, -0.065f, 0)));
    append_mesh(m, placed(capsule(0.016f, 0.025f, kHandSpacing), Vec3(0, -0.05f, 0.05f), kX, 0.6f));  // thumb
    return m;
}

TriangleMesh thigh_mesh() {
    TriangleMesh m = sphere(0.08f, kLegSpacing);  // hip ball
    append_mesh(m, hanging_limb(0.075f, 0.06f, kThighLength, kLegSpacing));
    return m;
}

TriangleMesh shin_mesh() {
    TriangleMesh m = hanging_limb(0.06f, kAnkleRadius, kShinLength, kLegSpacing);
    append_mesh(m, placed(rounded_box(kFootHalfExtents, kFootRounding, kLegSpacing), kFootCenter));
    return m;
}

// ---- the walk: phase p = 2π t / T; the left leg swings forward while sin p > 0.

float phase(float t) { return 2 * kPi * t / kRobotWalkSeconds; }

// Hip flexion (degrees about +X; negative swings the leg forward).
float hip_degrees(float p) { return -25.0f * std::sin(p); }
// Knee flexion (positive bends the shin back), largest at mid-swing.
float knee_degrees(float p) {
    const float swing = std::max(0.0f, std::cos(p));
    return 5.0f + 45.0f * swing * swing;
}

// How far one leg reaches below its hip joint in a pose: the body rides on
// whichever leg reaches lower (the stance leg), which gives the bob of a real
// walk, twice per stride. The foot's rounded box is lowest at a corner of its
// core box less the rounding radius; the ankle ball is checked too.
float leg_reach(float p) {
    const Quat hip = about(kX, hip_degrees(p)), knee = about(kX, knee_degrees(p));
    const auto below_hip = [&](Vec3 in_shin) { return -(hip * (Vec3(0, -kThighLength, 0) + knee * in_shin)).y; };
    float reach = below_hip(Vec3(0, -kShinLength, 0)) + kAnkleRadius;
    const Vec3 core = kFootHalfExtents - kFootRounding;
    for (float sy : {-1.0f, 1.0f})
        for (float sz : {-1.0f, 1.0f})
            reach = std::max(reach, below_hip(kFootCenter + Vec3(0, sy * core.y, sz * core.z)) + kFootRounding);
    return reach;
}

constexpr float kHipBelowTorso = 0.02f;  // hip joints relative to the torso node
constexpr float kGroundClearance = 0.002f;

Vec3 torso_translation(float t) {
    const float p = phase(t);
    const float reach = std::max(leg_reach(p), leg_reach(p + kPi));
    return Vec3(0.015f * std::sin(p), kHipBelowTorso + reach + kGroundClearance, 0);  // slight side sway
}

}  // namespace

GeneratedModel make_robot() {
    GeneratedModel robot;
    robot.scene.name = "robot";
    robot.loop_seconds = kRobotWalkSeconds;
    robot.animation_name = "walk";

    const int torso = robot.add_node("torso", -1, torso_translation(0), torso_mesh());
    const int head = robot.add_node("head", torso, Vec3(0, 0.54f, 0), head_mesh());
    struct Side {
        const char* suffix;
        float sign;   // +1 left (+X), −1 right
        float shift;  // phase offset: the right side runs half a stride behind
    };
    const Side sides[2] = {{"_l", 1.0f, 0.0f}, {"_r", -1.0f, kPi}};
    int upper_arm[2], forearm[2], hand[2], thigh[2], shin[2];
    for (int s = 0; s < 2; ++s) {
        const std::string x = sides[s].suffix;
        const float sign = sides[s].sign;
        upper_arm[s] = robot.add_node("upper_arm" + x, torso, Vec3(sign * kShoulderWidth, 0.44f, 0), upper_arm_mesh());
        forearm[s] = robot.add_node("forearm" + x, upper_arm[s], Vec3(0, -kUpperArmLength, 0), forearm_mesh());
        hand[s] = robot.add_node("hand" + x, forearm[s], Vec3(0, -kForearmLength, 0), hand_mesh());
        thigh[s] = robot.add_node("thigh" + x, torso, Vec3(sign * kHipWidth, -kHipBelowTorso, 0), thigh_mesh());
        shin[s] = robot.add_node("shin" + x, thigh[s], Vec3(0, -kThighLength, 0), shin_mesh());
    }

    const float T = kRobotWalkSeconds;
    constexpr int kKeys = 32;  // per loop: 16 per step
    auto& nodes = robot.scene.nodes;
    nodes[torso].translation = loop_translation_track(torso_translation, T, kKeys);
    nodes[torso].rotation = loop_rotation_track([](float t) { return about(kY, 4.0f * std::sin(phase(t))); }, T, kKeys);
    nodes[head].rotation = loop_rotation_track(
        [](float t) { return about(kY, -3.0f * std::sin(phase(t))) * about(kX, 3.0f); }, T, kKeys);
    for (int s = 0; s < 2; ++s) {
        const float shift = sides[s].shift, sign = sides[s].sign;
        nodes[thigh[s]].rotation =
            loop_rotation_track([=](float t) { return about(kX, hip_degrees(phase(t) + shift)); }, T, kKeys);
        nodes[shin[s]].rotation =
            loop_rotation_track([=](float t) { return about(kX, knee_degrees(phase(t) + shift)); }, T, kKeys);
        // Arms swing against the leg on their side, held slightly away from the body.
        nodes[upper_arm[s]].rotation = loop_rotation_track(
            [=](float t) { return about(kZ, sign * 6.0f) * about(kX, 20.0f * std::sin(phase(t) + shift)); }, T, kKeys);
        nodes[forearm[s]].rotation = loop_rotation_track(
            [=](float t) { return about(kX, -20.0f - 12.0f * std::max(0.0f, -std::sin(phase(t) + shift))); }, T, kKeys);
        nodes[hand[s]].rotation = loop_rotation_track(
            [=](float t) { return about(kX, -8.0f + 4.0f * std::sin(phase(t) + shift)); }, T, kKeys);
    }
    // Rest pose = the pose at t = 0, so a viewer without animation shows a natural stance.
    for (SceneNode& node : nodes) {
        if (node.rotation) node.rest.rotation = node.rotation->values.front();
        if (node.translation) node.rest.translation = node.translation->values.front();
    }
    return robot;
}

TriangleMesh make_ground() {
    TriangleMesh ground = grid_plane(8.0f, 8.0f, 160, 160);
    ground.name = "ground";
    return ground;
}

}  // namespace rsl::assets
