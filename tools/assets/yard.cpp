#include "tools/assets/yard.h"

#include <cmath>
#include <random>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tools/assets/primitives.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"

namespace rsl::assets {
namespace {

const Vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);
// Vertex spacings (m), tuned so each instance mesh has ~500 vertices.
constexpr float kCrateSpacing = 0.032f, kCupSpacing = 0.075f, kTopSpacing = 0.06f, kRingSpacing = 0.0525f;

TriangleMesh lathe(const Profile& profile, float spacing) {
    const auto samples = profile.sample(spacing);
    return revolve(samples, segments_for(samples, spacing));
}

TriangleMesh crate_mesh() { return rounded_box(Vec3(0.14f, 0.14f, 0.14f), 0.03f, kCrateSpacing); }

TriangleMesh cup_mesh() {
    Profile p(Vec2(0, 0));
    p.rounded_polyline({{0.11f, 0.0f}, {0.12f, 0.02f}, {0.14f, 0.28f}, {0.125f, 0.28f}, {0.11f, 0.035f}, {0.0f, 0.035f}},
                       0.015f);
    TriangleMesh m = lathe(p, kCupSpacing);
    TriangleMesh handle = torus(0.08f, 0.02f, kCupSpacing);
    transform_mesh(handle, translate_rotate(Vec3(0.16f, 0.15f, 0), kX, kPi / 2));
    append_mesh(m, handle);
    return m;
}

TriangleMesh top_mesh() {
    Profile p(Vec2(0, 0));
    p.rounded_polyline({{0.02f, 0.0f}, {0.16f, 0.12f}, {0.12f, 0.2f}, {0.03f, 0.22f}, {0.03f, 0.3f}, {0.0f, 0.3f}},
                       0.03f);
    return lathe(p, kTopSpacing);
}

TriangleMesh ring_mesh() { return torus(0.13f, 0.05f, kRingSpacing); }

float phase(float t) { return 2 * kPi * t / kYardLoopSeconds; }

}  // namespace

GeneratedModel make_yard(int instances) {
    if (instances < 1 || instances > kYardMaxInstances)
        throw Error(fmt::format("yard: {} instances is out of range [1, {}]", instances, kYardMaxInstances));
    GeneratedModel yard;
    yard.scene.name = fmt::format("yard-{}", instances);
    yard.loop_seconds = kYardLoopSeconds;
    yard.animation_name = "yard";

    const int side = int(std::ceil(std::sqrt(double(instances))));
    const float extent = float(side) + 2.0f;  // one instance per m², a metre of margin
    TriangleMesh ground = grid_plane(extent, extent, 120, 120);
    yard.add_node("ground", -1, Vec3(0), std::move(ground));

    const TriangleMesh meshes[4] = {crate_mesh(), cup_mesh(), top_mesh(), ring_mesh()};
    const char* names[4] = {"crate", "cup", "top", "ring"};
    std::mt19937 rng(20261201u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr int kKeys = 48;
    for (int i = 0; i < instances; ++i) {
        const TriangleMesh& mesh = meshes[i % 4];
        const float rest_height = -mesh.bounds().lo.y + 0.002f;
        // One draw per statement, so that every compiler makes the same yard
        // (a call's arguments are evaluated in an unspecified order); z before
        // x, the order GCC gave the yard the benchmarks measured.
        const float jitter_z = unit(rng);
        const float jitter_x = unit(rng);
        const Vec3 home((float(i % side) - 0.5f * float(side - 1)) + 0.3f * (jitter_x - 0.5f), rest_height,
                        (float(i / side) - 0.5f * float(side - 1)) + 0.3f * (jitter_z - 0.5f));
        const float offset = kYardLoopSeconds * unit(rng);  // its own phase
        const float tilt_z = unit(rng);
        const float tilt_x = unit(rng);
        const Vec3 axis = glm::normalize(Vec3(tilt_x - 0.5f, 1.0f, tilt_z - 0.5f));
        const int node = yard.add_node(fmt::format("{}_{:04d}", names[i % 4], i), -1, home, mesh);
        SceneNode& n = yard.scene.nodes[size_t(node)];
        switch (i % 3) {
            case 0:  // bounces 0.6 m high (a parabola each loop), turning once
                n.translation = loop_translation_track(
                    [=](float t) {
                        const float s = std::fmod(t + offset, kYardLoopSeconds) / kYardLoopSeconds;
                        return home + Vec3(0, 2.4f * s * (1 - s), 0);
                    },
                    kYardLoopSeconds, kKeys);
                n.rotation = loop_rotation_track([=](float t) { return glm::angleAxis(phase(t + offset), kY); },
                                                 kYardLoopSeconds, kKeys);
                break;
            case 1:  // tumbles about a tilted axis, hovering 0.3 m up
                n.translation = loop_translation_track(
                    [=](float t) { return home + Vec3(0, 0.3f + 0.05f * std::sin(phase(t + offset)), 0); },
                    kYardLoopSeconds, kKeys);
                n.rotation = loop_rotation_track([=](float t) { return glm::angleAxis(2 * phase(t + offset), axis); },
                                                 kYardLoopSeconds, kKeys);
                break;
            default:  // orbits its home on a 0.3 m circle, facing along the path
                n.translation = loop_translation_track(
                    [=](float t) {
                        const float p = phase(t + offset);
                        return home + 0.3f * Vec3(std::cos(p), 0, std::sin(p));
                    },
                    kYardLoopSeconds, kKeys);
                n.rotation = loop_rotation_track([=](float t) { return glm::angleAxis(-phase(t + offset), kY); },
                                                 kYardLoopSeconds, kKeys);
                break;
        }
        n.rest.rotation = n.rotation->values.front();
        n.rest.translation = n.translation->values.front();
    }
    return yard;
}

std::filesystem::path write_yard(const std::filesystem::path& dir, int instances, const std::string& environment) {
    const GeneratedModel yard = make_yard(instances);
    const std::string stem = fmt::format("yard-{}", instances);
    write_glb(dir / (stem + ".glb"), yard);

    const int side = int(std::ceil(std::sqrt(double(instances))));
    const float distance = 0.75f * float(side) + 1.5f;
    nlohmann::ordered_json scene;
    scene["name"] = stem;
    scene["gltf"] = stem + ".glb";
    scene["materials"] = {
        {"paint", {{"model", "blinn_phong"}, {"kd", {0.7, 0.32, 0.08}}, {"ks", {0.2, 0.2, 0.2}}, {"exponent", 25}}},
        {"floor", {{"model", "lambert"}, {"albedo", {0.55, 0.53, 0.5}}}}};
    scene["part_materials"] = {{"ground", "floor"}, {"*", "paint"}};
    scene["environment"] = {{"file", environment},
                            {"resolution", 32},
                            {"rotation", {{"axis", {0, 1, 0}}, {"degrees", 0}, {"degrees_per_second", 0}}}};
    scene["camera"] = {{"position", {0.55 * distance, 0.6 * distance, distance}},
                       {"target", {0, 0, 0}},
                       {"up", {0, 1, 0}},
                       {"fov_degrees", 45},
                       {"width", 640},
                       {"height", 480}};
    scene["animation"] = {{"start", 0}, {"end", kYardLoopSeconds}, {"fps", 24}};
    // The meshes as made (500-900 vertices each): the yard measures how the
    // frame grows with the part count, and scene files subdivide by default
    // (a cup would become 5,000 vertices).
    scene["subdivision"] = false;
    // The bench field settings (tools/bench/render_bench_cases.cpp bench_precompute), but the yard's reach.
    scene["precompute"] = {
        {"svdf", {{"resolution", 16}, {"clusters", 64}, {"vectors", 6}, {"supersampling", 2}}},
        {"ovdf",
         {{"shells", 13}, {"inner_radius", 0.4}, {"outer_radius", kYardOvdfReach}, {"cube_resolution", 16}, {"vdt_resolution", 16},
          {"vectors", 6}}}};
    const std::filesystem::path path = dir / (stem + ".json");
    write_file_atomically(path, scene.dump(2) + "\n");
    return path;
}

}  // namespace rsl::assets
