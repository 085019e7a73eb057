// The GPU pass timers measure the passes: nonzero, and no longer than the
// wall-clock time of the frame (under llvmpipe, whose timer queries span none
// of the work, by the clock around glFinish; on a GPU, by timer queries).
#include <catch2/catch.hpp>

#include <chrono>

#include "src/gl/gl_renderer.h"
#include "tests/gl/gl_test_support.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl {
namespace {

TEST_CASE("GPU pass timers report the time of the shading and pack passes", "[gl-renderer]") {
    test::gl_context();
    Scene scene = test::make_scene("timers", Color(0.6f));
    test::add_part(scene, test::make_plane(2.0f, 40, "ground"));
    Transform lifted;
    lifted.translation = Vec3(0, 0.5f, 0);
    test::add_part(scene, test::make_icosphere(0.3f, 4, "ball"), lifted);
    gl::GlRenderer gpu(scene, test::random_rsls(64, 5), PartFields{}, RenderOptions{});
    VertexColors colors = gpu.make_output();
    double wall_ms = 0;
    // Timer queries are read two frames late: run a few.
    for (int frame = 0; frame < 6; ++frame) {
        gpu.set_time(0.1f * frame);
        const auto start = std::chrono::steady_clock::now();
        gpu.shade(colors);  // shade() and the read back: the passes are done when it returns
        wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    const gl::PassTimings t = gpu.timings();
    INFO(gl::context_description() << ": shading " << t.shade_ms << " ms, frame " << wall_ms << " ms wall"
                               << (t.clock ? " (clock)" : " (timer queries)"));
    CHECK(t.shade_ms > 0.0);
    // A timer cannot exceed the frame it timed (the frame before the last, for queries: alike in size).
    CHECK(t.shade_ms < 2.0 * wall_ms + 1.0);
    if (t.clock) CHECK(t.shade_ms > 0.3 * wall_ms);  // the clock around glFinish spans the shading work
}

}  // namespace
}  // namespace rsl
