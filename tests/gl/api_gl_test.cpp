// The public API's GPU backends: "gl-current" shades into a GL buffer of the
// caller's context (what an engine draws with its own pipeline), "gl" into
// its own context; both give the CPU backend's colours.
#include <catch2/catch.hpp>

#include <thread>

#include "rsl/rsl.h"
#include "src/gl/gl.h"
#include "tests/api/api_test_scene.h"
#include "tests/gl/gl_test_support.h"

namespace rsl {
namespace {

VertexColors as_internal(const api::VertexColors& c) {
    VertexColors out;
    for (size_t p = 0; p < c.part_names.size(); ++p) {
        out.add_part(c.part_names[p], c.part_offsets[p + 1] - c.part_offsets[p]);
        for (size_t v = c.part_offsets[p]; v < c.part_offsets[p + 1]; ++v)
            out.parts[p][v - c.part_offsets[p]] = Color(c.rgb[3 * v], c.rgb[3 * v + 1], c.rgb[3 * v + 2]);
    }
    return out;
}

// The API tests' scene (tests/api/api_test_scene.h) in a folder of its own.
api::Scene api_scene(const std::string& folder) {
    return api::Scene::load(test::write_api_scene(test::scratch_dir(folder), "scene.json").string());
}

TEST_CASE("the API's gl-current backend fills a GL colour buffer of the caller's context with the CPU's colours", "[gl-api]") {
    const api::Scene scene = api_scene("api-gl");
    api::RenderSettings settings;
    settings.lights = 12;
    api::Renderer cpu(scene, settings);
    test::gl_context();  // the "engine's" context, current on this thread
    settings.backend = "gl-current";
    api::Renderer gpu(scene, settings);
    CHECK(gpu.backend() == "gl-current");
    const GLuint buffer = gpu.gl_color_buffer();
    REQUIRE(glIsBuffer(buffer));
    for (const float t : {0.1f, 0.6f}) {
        cpu.set_time(t);
        gpu.set_time(t);
        gpu.set_part_pose("orb", api::Pose{{0.2f * t, 0.05f, 0}, {1, 0, 0, 0}, {1, 1, 1}});
        cpu.set_part_pose("orb", api::Pose{{0.2f * t, 0.05f, 0}, {1, 0, 0, 0}, {1, 1, 1}});
        const api::VertexColors expected = cpu.shade();
        gpu.shade_gl();
        // Vertex i at byte 16·i: RGBA32F, parts in scene order.
        const size_t n = expected.vertex_count();
        std::vector<float> rgba(4 * n);
        glBindBuffer(GL_ARRAY_BUFFER, buffer);
        glGetBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(rgba.size() * sizeof(float)), rgba.data());
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        gl::check_gl("reading the colour buffer");
        api::VertexColors from_buffer = expected;
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) from_buffer.rgb[3 * i + c] = rgba[4 * i + c];
        const test::ColorDifference d = test::compare_colors(as_internal(from_buffer), as_internal(expected), 1e-3);
        INFO("t = " << t << ": relative L2 " << d.relative_l2 << ", " << d.over_tolerance << " of " << d.vertices);
        CHECK(d.mean_luminance > 1e-3);
        CHECK(d.relative_l2 < 1e-5);
        CHECK(d.over_tolerance <= d.vertices / 1000);
        // shade() reads the same buffer back.
        CHECK(gpu.shade().rgb == from_buffer.rgb);
    }
}

TEST_CASE("the API's gl backend renders the CPU's colours and image; gl-current without a context is refused", "[gl-api]") {
    const api::Scene scene = api_scene("api-gl-own");
    api::RenderSettings settings;
    settings.lights = 8;
    // Each backend forms its own image (the GL one rasterizes): with the
    // per-pixel passes off, the two images compare the vertex pipelines.
    settings.pixel_shadows = "off";
    settings.pixel_highlights = false;
    api::Renderer cpu(scene, settings);
    settings.backend = "gl";
    api::Renderer gpu(scene, settings);
    CHECK(gpu.device().find("OpenGL") != std::string::npos);
    const test::ColorDifference d = test::compare_colors(as_internal(gpu.shade()), as_internal(cpu.shade()), 1e-3);
    CHECK(d.relative_l2 < 1e-5);
    const api::ImageError image = api::compare(gpu.render_image(), cpu.render_image());
    CHECK(image.covered > 1000);
    CHECK(image.relative_l2 < 1e-4);

    // A fresh thread has no current context.
    std::string message;
    std::thread([&] {
        settings.backend = "gl-current";
        message = test::error_of([&] { api::Renderer(scene, settings); });
    }).join();
    CHECK(message.find("no OpenGL context is current") != std::string::npos);
}

}  // namespace
}  // namespace rsl
