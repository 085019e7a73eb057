// RenderSession (src/backend/render_session.h): the set-up, renderer and
// image every tool starts from render a scene exactly as its parts do by
// hand (prepare_render, make_renderer, set_time, shade, form_image).
#include <catch2/catch.hpp>

#include <filesystem>

#include "src/backend/render_session.h"
#include "tests/api/api_test_scene.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

fs::path session_scene() {
    const fs::path folder = fs::path(RSL_BINARY_DIR) / "render-session-test";
    fs::create_directories(folder);
    return test::write_api_scene(folder, "scene.json");
}

void require_equal(const VertexColors& a, const VertexColors& b) {
    REQUIRE(a.parts.size() == b.parts.size());
    for (size_t p = 0; p < a.parts.size(); ++p) {
        REQUIRE(a.parts[p].size() == b.parts[p].size());
        for (size_t v = 0; v < a.parts[p].size(); ++v) {
            INFO("part " << p << " vertex " << v);
            REQUIRE(a.parts[p][v].r == b.parts[p][v].r);
            REQUIRE(a.parts[p][v].g == b.parts[p][v].g);
            REQUIRE(a.parts[p][v].b == b.parts[p][v].b);
        }
    }
}

TEST_CASE("A session shades and forms images as its parts do by hand", "[backend][session]") {
    const fs::path path = session_scene();
    RenderOptions options;
    options.environment_light_count = 12;
    RenderSession session(path, options);
    CHECK(session.backend() == Backend::Cpu);
    CHECK(session.setup().environment_lights.light_count() == 12);

    const RenderSetup setup = prepare_render(path, options);
    const auto renderer = make_renderer(Backend::Cpu, *setup.scene, setup.environment_lights, setup.fields, options);
    VertexColors colors = renderer->make_output();
    renderer->keep_image_terms(true);
    for (const float t : {0.0f, 0.37f, 0.9f}) {
        INFO("t = " << t);
        renderer->set_time(t);
        renderer->shade(colors);
        require_equal(session.shade(t), colors);
        require_equal(session.colors(), colors);
        CHECK(session.renderer().time() == t);

        const PinholeCamera expected = PinholeCamera::at_time(setup.scene->camera, t, 40, 30);
        const PinholeCamera camera = session.camera(40, 30);
        CHECK(camera.width == 40);
        CHECK(camera.height == 30);
        const Image by_hand = renderer->form_image(colors, expected);
        const Image image = session.image(camera);
        REQUIRE(image.pixels.size() == by_hand.pixels.size());
        size_t differing = 0;
        for (size_t i = 0; i < image.pixels.size(); ++i) differing += image.pixels[i] != by_hand.pixels[i];
        CHECK(differing == 0);
    }
    // Width 0 is the camera's own.
    CHECK(session.camera().width == setup.scene->camera.width);
    CHECK(session.camera().height == setup.scene->camera.height);
}

TEST_CASE("A session's image needs a shade that kept the image's terms", "[backend][session]") {
    RenderOptions options;
    options.environment_light_count = 8;
    RenderSession session(session_scene(), options);
    CHECK_THROWS_WITH(session.image(session.camera(16, 12)), Catch::Contains("needs a shade() of the current frame"));
    session.shade(0.2f, false);
    CHECK_THROWS_WITH(session.image(session.camera(16, 12)), Catch::Contains("keep_image_terms(true)"));
    session.shade(0.2f);
    CHECK(session.image(session.camera(16, 12)).width == 16);
}

}  // namespace
}  // namespace rsl
