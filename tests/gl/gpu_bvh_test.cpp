// The GPU's BVH (src/gl/gpu_bvh.h) against Embree (RayScene with the same
// origin filter): the same hit or miss on at least 99.99% of the rays, with
// the disagreements printed; the refit follows moved parts.
#include <catch2/catch.hpp>

#include <filesystem>
#include <random>

#include "src/formats/scene_file.h"
#include "src/gl/gpu_bvh.h"
#include "src/rays/posed_scene.h"
#include "tests/gl/gl_test_support.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

struct Rays {
    std::vector<Vec3> origins, directions;
};

// Shadow rays as the ray-traced baseline casts them: from vertices' ray
// origins (every `stride`-th vertex of every part), into random directions
// above their shading normal; and rays between random points of the scene's box.
Rays sample_rays(const Scene& scene, const PosedScene& posed, int stride, int per_vertex, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Rays rays;
    Bounds box;
    for (size_t p = 0; p < scene.parts.size(); ++p)
        for (size_t v = 0; v < scene.parts[p].mesh.vertex_count(); v += size_t(stride)) {
            const SurfacePoint x = posed.vertex(int(p), int(v));
            box.extend(x.position);
            for (int k = 0; k < per_vertex; ++k) {
                Vec3 d = test::random_vec3(unit, rng);
                if (glm::dot(d, x.offset_normal) < 0.0f) d = -d;
                if (glm::length(d) < 1e-3f) continue;
                rays.origins.push_back(x.ray_origin());
                rays.directions.push_back(glm::normalize(d));
            }
        }
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    for (int k = 0; k < 20000; ++k) {
        const Vec3 a = box.lo + (box.hi - box.lo) * test::random_vec3(u01, rng);
        const Vec3 b = box.lo + (box.hi - box.lo) * test::random_vec3(u01, rng);
        rays.origins.push_back(a), rays.directions.push_back(glm::normalize(b - a));
    }
    return rays;
}

// Embree's answers (RayScene(true), the truth's and the CPU baseline's) and the GPU's, at time t.
size_t disagreements(const Scene& scene, gl::GpuBvh& bvh, float t, int stride, int per_vertex, float t_far,
                     size_t& total) {
    const PosedScene posed(scene, t);
    std::vector<Mat4> transforms;
    for (size_t p = 0; p < scene.parts.size(); ++p) transforms.push_back(posed.part_transform(int(p)));
    bvh.set_poses(transforms);
    const Rays rays = sample_rays(scene, posed, stride, per_vertex, 11 + uint32_t(100 * t));
    const std::vector<uint8_t> gpu = bvh.occluded(rays.origins, rays.directions, t_far);
    size_t differ = 0, blocked = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        const bool embree = posed.rays().occluded(rays.origins[i], rays.directions[i], 0.0f, t_far);
        blocked += embree ? 1 : 0;
        differ += (gpu[i] != 0) != embree ? 1 : 0;
    }
    total = gpu.size();
    WARN(scene.name << " at t = " << t << ": " << differ << " of " << total << " rays disagree (" << blocked
                    << " blocked by Embree)");
    CHECK(blocked > total / 20);       // rays that meet geometry: the comparison means something
    CHECK(blocked < total - total / 20);
    return differ;
}

TEST_CASE("GPU BVH rays equal Embree's: a moving sphere, a box on a ground, instances", "[gl-bvh]") {
    test::gl_context();
    Scene scene = test::make_scene("bvh");
    test::add_part(scene, test::make_plane(3.0f, 16, "ground"));
    Transform big, box;
    big.translation = Vec3(0, 0.45f, 0);
    box.translation = Vec3(-0.6f, 0.2f, -0.5f);
    box.rotation = glm::angleAxis(0.4f, Vec3(0, 1, 0));
    test::add_part(scene, test::make_icosphere(0.4f, 3, "big"), big);
    test::add_part(scene, test::make_flat_box(Vec3(0.3f, 0.2f, 0.25f), 4, "box"), box);
    const TriangleMesh ball = test::make_icosphere(0.1f, 2, "ball");
    for (int i = 0; i < 40; ++i) {
        Transform pose;
        pose.translation = Vec3(-1.2f + 0.3f * float(i % 8), 0.1f + 0.25f * float(i % 3), 0.6f + 0.2f * float(i / 8));
        pose.scale = Vec3(1.0f + 0.2f * float(i % 4), 1.0f, 1.0f);
        test::add_part(scene, ball, pose);
    }
    Vec3Track path;  // the big sphere slides across the box's place
    path.times = {0.0f, 1.0f};
    path.values = {Vec3(0, 0.45f, 0), Vec3(-0.6f, 0.7f, -0.4f)};
    scene.nodes[scene.parts[1].node].translation = path;
    gl::GpuBvh bvh(scene);
    CHECK(bvh.stats().meshes == 4);  // ground, sphere, box, one ball for 40 parts
    for (const float t : {0.0f, 0.5f, 1.0f}) {
        size_t total = 0;
        const size_t differ = disagreements(scene, bvh, t, 1, 8, 1e30f, total);
        CHECK(double(differ) <= 1e-4 * double(total));
    }
    size_t total = 0;  // a short t_far: rays end before most blockers
    CHECK(double(disagreements(scene, bvh, 0.5f, 2, 4, 0.3f, total)) <= 1e-4 * double(total));
}

TEST_CASE("GPU BVH rays equal Embree's on the robot", "[gl-bvh]") {
    const std::filesystem::path source(RSL_SOURCE_DIR);
    if (!std::filesystem::exists(source / "assets/generated/robot.glb")) {
        WARN("SKIPPED: assets/generated/robot.glb is missing (build the generated_assets target)");
        return;
    }
    test::gl_context();
    const Scene scene = load_scene(source / "assets/scenes/robot.json");
    gl::GpuBvh bvh(scene);
    const gl::BvhStats& stats = bvh.stats();
    WARN("robot BVH: " << stats.meshes << " meshes, " << stats.triangles << " triangles, " << stats.bottom_nodes
                       << " nodes, depth " << stats.bottom_depth << ", built in " << stats.build_ms << " ms");
    CHECK(stats.bottom_depth <= gl::kBvhStack - 1);
    for (const float t : {0.0f, 0.8f}) {
        size_t total = 0;
        const size_t differ = disagreements(scene, bvh, t, 3, 4, 1e30f, total);
        CHECK(double(differ) <= 1e-4 * double(total));
    }
}

TEST_CASE("GPU BVH: hand-made rays", "[gl-bvh]") {
    test::gl_context();
    Scene scene = test::make_scene("wall");
    Transform up;
    up.translation = Vec3(0, 1, 0);
    test::add_part(scene, test::make_plane(2.0f, 2, "wall"), up);  // y = 1, facing +y
    gl::GpuBvh bvh(scene);
    bvh.set_poses({scene.nodes[scene.parts[0].node].rest.matrix()});
    const std::vector<Vec3> origins{Vec3(0.1f, 0, 0.2f), Vec3(0.1f, 0, 0.2f), Vec3(0.1f, 0, 0.2f), Vec3(3, 0, 0),
                                    Vec3(0.1f, 1.0f - 1e-6f, 0.2f)};
    const std::vector<Vec3> directions{Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)};
    // Straight at the wall: blocked; away: free; t_far before the wall: free;
    // beside it: free; from just behind its surface, leaving through its
    // front within the exit offsets: free (the origin is on that surface).
    const std::vector<uint8_t> want{1, 0, 0, 0, 0};
    const std::vector<uint8_t> far = bvh.occluded(origins, directions, 1e30f);
    const std::vector<uint8_t> near = bvh.occluded({origins[2]}, {directions[2]}, 0.5f);
    CHECK(far[0] == 1);
    CHECK(far[1] == 0);
    CHECK(near[0] == 0);
    CHECK(far[3] == 0);
    CHECK(far[4] == 0);
    // Entering through its front from just above it is blocked.
    CHECK(bvh.occluded({Vec3(0.1f, 1.0f + 1e-6f, 0.2f)}, {Vec3(0, -1, 0)}, 1e30f)[0] == 1);
    // Moving the wall away frees the first ray (the refit follows).
    Transform aside = up;
    aside.translation = Vec3(5, 1, 0);
    bvh.set_poses({aside.matrix()});
    CHECK(bvh.occluded({origins[0]}, {directions[0]}, 1e30f)[0] == 0);
}

}  // namespace
}  // namespace rsl
