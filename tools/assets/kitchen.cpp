#include "tools/assets/kitchen.h"

#include <cmath>

#include "tools/assets/primitives.h"

namespace rsl::assets {
namespace {

// Vertex spacing (m) per object, tuned so the five parts total ~80k vertices
// (room ~18k, teapot ~25k, bowl ~14k, cup ~11k, chair ~12k), the small objects
// that receive the finest shadows densest.
constexpr float kTeapotSpacing = 0.0047f;
constexpr float kBowlSpacing = 0.0052f;
constexpr float kCupSpacing = 0.0032f;
constexpr float kChairSpacing = 0.0097f;

const Vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

TriangleMesh placed(TriangleMesh mesh, Vec3 at, Vec3 axis = kY, float radians = 0) {
    transform_mesh(mesh, translate_rotate(at, axis, radians));
    return mesh;
}

TriangleMesh lathe(Profile& profile, float spacing) {
    const auto samples = profile.sample(spacing);
    return revolve(samples, segments_for(samples, spacing));
}

// Floor sheet (5 m × 5 m, 5 cm cells) and the counter block against the back (−Z).
TriangleMesh room_mesh() {
    TriangleMesh m = grid_plane(5.0f, 5.0f, 100, 100);
    append_mesh(m, placed(rounded_box(Vec3(1.0f, kCounterTop / 2, 0.32f), 0.03f, 0.03f),
                          Vec3(0, kCounterTop / 2, -0.6f)));
    return m;
}

// Profiles run from the bottom of the axis, out and up the outside, and back
// to the axis along the top (or down the inside), solid on the left.
TriangleMesh teapot_mesh_in_kitchen(float spacing = kTeapotSpacing) {
    Profile body(Vec2(0, 0));
    body.rounded_polyline({{0.075f, 0.0f}, {0.118f, 0.035f}, {0.128f, 0.09f}, {0.112f, 0.15f}, {0.08f, 0.172f},
                           // the lid: a step in, a dome, and a knob on a short stem
                           {0.074f, 0.176f}, {0.072f, 0.184f}, {0.045f, 0.204f}, {0.014f, 0.212f},
                           {0.012f, 0.222f}, {0.022f, 0.228f}, {0.016f, 0.238f}, {0.0f, 0.238f}},
                          0.5f);  // large: corners round into one another, so the body curves smoothly
    TriangleMesh m = lathe(body, spacing);

    // Spout: a tapered tube with an open mouth (a bore down to a floor), its
    // base buried in the body, tilted 50° towards +X.
    Profile spout(Vec2(0, 0));
    spout.rounded_polyline({{0.032f, 0.0f}, {0.015f, 0.14f}, {0.009f, 0.14f}, {0.009f, 0.11f}, {0.0f, 0.11f}}, 0.01f);
    append_mesh(m, placed(lathe(spout, spacing), Vec3(0.085f, 0.05f, 0), kZ, -50.0f * kPi / 180));

    // Handle: a ring in the XY plane whose inner half is hidden inside the body.
    append_mesh(m, placed(torus(0.058f, 0.012f, spacing), Vec3(-0.125f, 0.1f, 0), kX, kPi / 2));
    return m;
}

TriangleMesh bowl_mesh() {
    Profile p(Vec2(0, 0));
    p.rounded_polyline({{0.045f, 0.0f}, {0.05f, 0.012f}, {0.1f, 0.05f}, {0.13f, 0.095f},  // foot and outside
                        {0.124f, 0.098f},                                                   // rim
                        {0.096f, 0.058f}, {0.045f, 0.022f}, {0.0f, 0.018f}},                // inside
                       0.2f);
    return lathe(p, kBowlSpacing);
}

TriangleMesh cup_mesh() {
    Profile p(Vec2(0, 0));
    p.rounded_polyline({{0.035f, 0.0f}, {0.04f, 0.008f}, {0.046f, 0.095f},  // outside
                        {0.041f, 0.095f},                                    // rim
                        {0.036f, 0.012f}, {0.0f, 0.012f}},                   // inside
                       0.006f);
    TriangleMesh m = lathe(p, kCupSpacing);
    append_mesh(m, placed(torus(0.028f, 0.0065f, kCupSpacing), Vec3(0.054f, 0.05f, 0), kX, kPi / 2));
    return m;
}

TriangleMesh chair_mesh() {
    TriangleMesh m = rounded_box(Vec3(0.22f, 0.025f, 0.22f), 0.02f, kChairSpacing);  // seat
    transform_mesh(m, translate_rotate(Vec3(0, 0.45f, 0)));
    for (float sx : {-1.0f, 1.0f})
        for (float sz : {-1.0f, 1.0f})
            append_mesh(m, placed(rounded_box(Vec3(0.02f, 0.215f, 0.02f), 0.015f, kChairSpacing),
                                  Vec3(sx * 0.19f, 0.215f, sz * 0.19f)));
    // Back posts and the backrest on the +Z side (away from the counter).
    for (float sx : {-1.0f, 1.0f})
        append_mesh(m, placed(rounded_box(Vec3(0.02f, 0.25f, 0.02f), 0.015f, kChairSpacing), Vec3(sx * 0.19f, 0.72f, 0.19f)));
    append_mesh(m, placed(rounded_box(Vec3(0.21f, 0.08f, 0.018f), 0.015f, kChairSpacing), Vec3(0, 0.84f, 0.19f)));
    return m;
}

float phase(float t) { return 2 * kPi * t / kKitchenLoopSeconds; }

}  // namespace

// 2.5 times the kitchen's vertex spacing: 6,767 vertices, so that
// scenes of many instances stay light.
TriangleMesh make_teapot() { return teapot_mesh_in_kitchen(2.5f * kTeapotSpacing); }

GeneratedModel make_kitchen() {
    GeneratedModel kitchen;
    kitchen.scene.name = "kitchen";
    kitchen.loop_seconds = kKitchenLoopSeconds;
    kitchen.animation_name = "tabletop";

    const Vec3 teapot_home(-0.35f, kCounterTop, -0.55f), cup_home(0.45f, kCounterTop, -0.5f);
    const int room = kitchen.add_node("room", -1, Vec3(0), room_mesh());
    const int teapot = kitchen.add_node("teapot", room, teapot_home, teapot_mesh_in_kitchen());
    kitchen.add_node("bowl", room, Vec3(0.05f, kCounterTop, -0.65f), bowl_mesh());
    const int cup = kitchen.add_node("cup", room, cup_home, cup_mesh());
    kitchen.add_node("chair", room, Vec3(0.1f, 0, 0.25f), chair_mesh());

    constexpr int kKeys = 48;
    auto& nodes = kitchen.scene.nodes;
    // The teapot slides 15 cm either way along the counter and turns ±35°.
    nodes[teapot].translation = loop_translation_track(
        [=](float t) { return teapot_home + Vec3(0.15f * std::sin(phase(t)), 0, 0); }, kKitchenLoopSeconds, kKeys);
    nodes[teapot].rotation = loop_rotation_track(
        [](float t) { return glm::angleAxis(0.6f * std::sin(phase(t)), kY); }, kKitchenLoopSeconds, kKeys);
    // The cup circles (8 cm radius), its handle always facing outwards.
    nodes[cup].translation = loop_translation_track(
        [=](float t) {
            const float p = phase(t);
            return cup_home + 0.08f * Vec3(std::cos(p) - 1, 0, std::sin(p));
        },
        kKitchenLoopSeconds, kKeys);
    nodes[cup].rotation = loop_rotation_track([](float t) { return glm::angleAxis(-phase(t), kY); },
                                              kKitchenLoopSeconds, kKeys);
    for (SceneNode& node : nodes) {
        if (node.rotation) node.rest.rotation = node.rotation->values.front();
        if (node.translation) node.rest.translation = node.translation->values.front();
    }
    return kitchen;
}

}  // namespace rsl::assets
