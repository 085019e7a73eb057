// The GPU's vertex pass culls per block as the CPU renderer does: each
// workgroup's light bits per candidate occluder equal the CPU's
// block_may_be_shadowed over the same block (src/shading/culling.h is the one
// definition of the tests), and an OpenGL context older than 4.3 is refused
// with a message that names what was found.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdlib>
#include <random>

#include <unistd.h>

#include "src/core/error.h"

#include "src/gl/gl_renderer.h"
#include "src/render/cpu_renderer.h"
#include "tests/gl/gl_test_support.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

// Balls at random poses on a ground, one shared field, a sphere light and
// environment squares: many blocks, each with its own candidate lists.
Scene random_crowd(std::mt19937& rng, int balls, const TriangleMesh& ball) {
    Scene scene = test::make_scene("crowd", Color(0.6f));
    test::add_part(scene, test::make_plane(4.0f, 32, "ground"));
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < balls; ++i) {
        Transform pose;
        const Vec3 draw = test::random_vec3(u, rng);
        pose.translation = Vec3(1.8f * draw.x, 0.15f + 0.3f * (draw.y + 1.0f), 1.8f * draw.z);
        const float angle = 3.0f * u(rng);
        const Vec2 axis_xz = test::random_vec2(u, rng);
        pose.rotation = glm::angleAxis(angle, glm::normalize(Vec3(axis_xz.x, 1.0f, axis_xz.y)));
        pose.scale = Vec3(0.7f + 0.3f * (u(rng) + 1.0f));
        test::add_part(scene, ball, pose);
    }
    LocalLight light;
    light.radius = 0.05f;
    light.power = Color(2.0f);
    light.position = Vec3(0.3f, 1.2f, -0.2f);
    scene.lights.push_back(light);
    scene.camera.position = Vec3(0, 3, 4);
    return scene;
}

TEST_CASE("GPU block lists equal the CPU's block culling for random poses", "[gl-renderer]") {
    test::gl_context();
    const TriangleMesh ball = test::make_icosphere(0.15f, 2, "ball");
    Scene two = test::make_scene("two", Color(0.6f));
    test::add_part(two, ball);
    test::add_part(two, ball);
    two.precompute.ovdf_shells = 4, two.precompute.ovdf_cube_resolution = 8;
    two.precompute.ovdf_vdt_resolution = 16, two.precompute.ovdf_vectors = 4, two.precompute.ovdf_outer_radius = 4.0f;
    FieldBakeOptions bake;
    bake.self_visibility = false;
    const PartFields ball_fields = bake_part_fields(two, bake);

    std::mt19937 rng(20261205);
    size_t blocks = 0, part_bits = 0, kept_bits = 0, differing_bits = 0;
    for (int trial = 0; trial < 4; ++trial) {
        const Scene scene = random_crowd(rng, 30 + 10 * trial, ball);
        PartFields fields;
        fields.self.assign(scene.parts.size(), nullptr);
        fields.occluder.assign(scene.parts.size(), ball_fields.occluder[0]);
        RenderOptions options;
        options.exact_shapes = false;
        const EnvironmentLights lights = test::random_rsls(20 + 5 * trial, 7u + unsigned(trial));
        CpuRenderer cpu(scene, lights, fields, options);
        gl::GlRenderer gpu(scene, lights, fields, options);
        cpu.set_time(0.0f);
        gpu.set_time(0.0f);
        const std::vector<std::vector<uint32_t>> gpu_bits = gpu.block_candidate_lights();
        REQUIRE(gpu_bits.size() == cpu.block_count());
        const OccluderLists& lists = cpu.frame().occluder_lists();
        for (const uint32_t word : lists.candidate_lights) part_bits += size_t(std::popcount(word));
        for (size_t b = 0; b < cpu.block_count(); ++b) {
            const std::vector<uint32_t> expected = cpu.block_candidate_lights(b);
            REQUIRE(gpu_bits[b].size() == expected.size());
            for (size_t w = 0; w < expected.size(); ++w) {
                kept_bits += size_t(std::popcount(expected[w]));
                differing_bits += size_t(std::popcount(expected[w] ^ gpu_bits[b][w]));
            }
        }
        blocks += cpu.block_count();
    }
    INFO(blocks << " blocks: " << part_bits << " part-level (light, occluder) bits, the blocks keep " << kept_bits
                << ", GPU and CPU differ in " << differing_bits);
    // The block tests must cut a good share, and the two must agree but for
    // a test on a knife edge of float rounding.
    CHECK(blocks > 100);
    CHECK(kept_bits < part_bits);
    CHECK(kept_bits > part_bits / 20);
    CHECK(differing_bits <= kept_bits / 10000 + 2);
}

// Run by the case below in a process of its own, whose contexts Mesa makes
// report OpenGL 4.1 (MESA_GL_VERSION_OVERRIDE is read once per process).
TEST_CASE("A context that reports 4.1 gets a clear refusal", "[.old-context]") {
    std::string message;
    try {
        gl::HeadlessContext old;  // may itself refuse the version
        Scene scene = test::make_scene("old", Color(0.6f));
        test::add_part(scene, test::make_icosphere(0.3f, 1, "ball"));
        gl::GlRenderer renderer(scene, test::random_rsls(4, 3), PartFields{}, RenderOptions{});
    } catch (const Error& e) {
        message = e.what();
    }
    INFO(message);
    // What was found and what is needed (the context's refusal or the
    // renderer's, not a shader's compile log).
    CHECK(message.find("OpenGL 4.1") != std::string::npos);
    CHECK((message.find("needs OpenGL 4.3") != std::string::npos ||
           message.find("OpenGL ≥ 4.3 core needed") != std::string::npos));
}

TEST_CASE("An OpenGL context older than 4.3 is refused with what was found", "[gl-renderer]") {
    test::gl_context();
    // Only Mesa makes its contexts report MESA_GL_VERSION_OVERRIDE's version.
    if (gl::context_description().find("Mesa") == std::string::npos) return;
    const std::string command = "MESA_GL_VERSION_OVERRIDE=4.1 /proc/" + std::to_string(getpid()) +
                                "/exe '[.old-context]' > /dev/null 2>&1";
    CHECK(std::system(command.c_str()) == 0);
}

}  // namespace
}  // namespace rsl
