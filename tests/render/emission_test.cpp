// Emission (src/core/emission.h): the same scene with and without emissive
// materials differs by exactly the emission, per vertex (the CPU renderer
// and the truth), per pixel (image formation and the per-pixel truth take an
// emissive texture at each pixel's texture coordinates), and under live edits
// of the `emissive` parameter. The expected emission is evaluated here,
// independently of Texture::sample.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "src/core/emission.h"
#include "src/image/image_formation.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/render/render_test_scenes.h"
#include "tests/test_support.h"

namespace rsl {
namespace {

// An emissive texture of distinct texels (5 × 3, repeating), linear RGB.
std::shared_ptr<Texture> glow_texture() {
    auto texture = std::make_shared<Texture>();
    texture->name = "glow";
    texture->image = Image(5, 3, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            texture->image.set_rgb(x, y, Color(0.1f + 0.2f * float(x), 0.9f - 0.3f * float(y), 0.05f * float(x * y)));
    return texture;
}

// Bilinear between texel centres, repeating: written out here as a reference.
Color bilinear_repeat(const Image& image, const Vec2& uv) {
    const double x = double(uv.x) * image.width - 0.5, y = double(uv.y) * image.height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    const auto texel = [&](double i, double j) {
        const int w = image.width, h = image.height;
        const int a = ((int(i) % w) + w) % w, b = ((int(j) % h) + h) % h;
        const float* p = &image.pixels[3 * (size_t(b) * size_t(w) + size_t(a))];
        return DVec3(p[0], p[1], p[2]);
    };
    const DVec3 c = (1 - fx) * (1 - fy) * texel(x0, y0) + fx * (1 - fy) * texel(x0 + 1, y0) +
                    (1 - fx) * fy * texel(x0, y0 + 1) + fx * fy * texel(x0 + 1, y0 + 1);
    return Color(c);
}

const Color kGroundGlow(0.5f, 0.8f, 1.2f), kBoxGlow(0.3f, 0.2f, 0.1f);

// box_over_coarse_ground's textured ground (a layered part) with an emissive
// texture over it, and its box (Lambert) glowing evenly.
Scene glowing(Scene scene) {
    scene.materials[1].emissive = kGroundGlow;
    scene.materials[1].emissive_texture = glow_texture();
    scene.materials[0].emissive = kBoxGlow;
    return scene;
}

// The emission expected at a point of part p of `scene` with texture coordinates uv.
Color expected_emission(const Scene& scene, size_t p, const Vec2& uv) {
    const MaterialDesc& m = scene.materials[size_t(scene.parts[p].material)];
    return m.emissive_texture ? m.emissive * bilinear_repeat(m.emissive_texture->image, uv) : m.emissive;
}

// `with` − `without` against the emission expected at every vertex: to
// float rounding of the sum (relative 1e-6).
void check_vertex_emission(const Scene& scene, const VertexColors& with, const VertexColors& without) {
    REQUIRE(with.parts.size() == scene.parts.size());
    int checked = 0;
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const TriangleMesh& mesh = scene.parts[p].mesh;
        REQUIRE(with.layered(p) == without.layered(p));
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            const Vec2 uv = mesh.texcoords.empty() ? Vec2(0) : mesh.texcoords[v];
            const Color expected = expected_emission(scene, p, uv);
            // A layered part's emission is in its specular layer (the base colour texture does not scale it).
            const Color added = with.layered(p) ? with.specular[p][v] - without.specular[p][v]
                                                : with.parts[p][v] - without.parts[p][v];
            if (with.layered(p)) REQUIRE(with.parts[p][v] == without.parts[p][v]);
            const Color total = with.layered(p) ? with.specular[p][v] : with.parts[p][v];
            for (int c = 0; c < 3; ++c) {
                INFO("part " << p << " vertex " << v << " channel " << c);
                REQUIRE(std::abs(added[c] - expected[c]) <= 1e-6f * std::max(1.0f, total[c]));
            }
            ++checked;
        }
    }
    CHECK(checked > 100);
}

RenderOptions per_vertex_options() {
    RenderOptions options;
    options.pixel_shadows = PixelShadows::Off;
    options.pixel_highlights = false;
    return options;
}

TEST_CASE("Emission adds exactly its radiance to the CPU renderer's vertex colours", "[render][emission]") {
    const Scene plain = test::box_over_coarse_ground(true);
    const Scene glow = glowing(plain);
    const RslSet lights = test::random_rsls(8, 3);
    CpuRenderer without(plain, lights, {}, RenderOptions{}), with(glow, lights, {}, RenderOptions{});
    const VertexColors a = with.shade(), b = without.shade();
    check_vertex_emission(glow, a, b);
    // At unit texture too (what the API and `rsl compare` of layered files see).
    const VertexColors folded_a = a.at_unit_texture(), folded_b = b.at_unit_texture();
    for (size_t v = 0; v < folded_a.parts[0].size(); ++v)
        for (int c = 0; c < 3; ++c)
            REQUIRE(folded_a.parts[0][v][c] - folded_b.parts[0][v][c] ==
                    Approx(expected_emission(glow, 0, glow.parts[0].mesh.texcoords[v])[c]).epsilon(1e-5).margin(1e-6));
    // The colours record the emission they hold, for image formation.
    REQUIRE(a.emission.size() == 2);
    CHECK(a.emission[0].texture == glow.materials[1].emissive_texture);
    CHECK(a.emission[1].emissive == kBoxGlow);
}

TEST_CASE("Editing `emissive` changes the vertex colours by the emission, and nothing else", "[render][emission]") {
    const Scene plain = test::box_over_coarse_ground(true);
    Scene glow = glowing(plain);
    const RslSet lights = test::random_rsls(8, 3);
    CpuRenderer without(plain, lights, {}, RenderOptions{}), with(plain, lights, {}, RenderOptions{});
    const VertexColors b = without.shade();
    const int tiles = with.materials().find("tiles");
    const auto table = with.materials().table(tiles);
    with.set_material_parameter("tiles", "emissive", {0.2f, 0.4f, 0.6f});
    with.set_material_parameter("white", "emissive", {0.3f, 0.2f, 0.1f});
    CHECK(with.materials().table(tiles) == table);  // not the BRDF's: no table rebuilt
    // The edited ground has no emissive texture: its emission is the factor alone.
    glow.materials[1].emissive = Color(0.2f, 0.4f, 0.6f);
    glow.materials[1].emissive_texture = nullptr;
    const VertexColors a = with.shade();
    check_vertex_emission(glow, a, b);
    // Bad values are refused naming the material and the parameter, and change nothing.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const std::vector<float>& bad : std::vector<std::vector<float>>{{-1, 0, 0}, {nan}, {1e30f, 0, 0}, {1, 2}}) {
        const std::string error = test::error_of([&] { with.set_material_parameter("tiles", "emissive", bad); });
        INFO(error);
        CHECK(error.find("material 'tiles'") != std::string::npos);
        CHECK(error.find("'emissive'") != std::string::npos);
    }
    CHECK(with.materials().desc(tiles).emissive == Color(0.2f, 0.4f, 0.6f));
    const VertexColors again = with.shade();
    for (size_t p = 0; p < a.parts.size(); ++p) CHECK(again.parts[p] == a.parts[p]);
}

// The hit of the primary ray through pixel (x, y)'s centre.
RayHit pixel_hit(const PosedScene& posed, const PinholeCamera& camera, int x, int y) {
    return posed.rays().intersect(camera.eye, camera.direction(float(x) + 0.5f, float(y) + 0.5f));
}

TEST_CASE("An emissive texture is taken per pixel in images: blend of what is reflected + emission at the pixel",
          "[render][emission]") {
    const Scene plain = test::box_over_coarse_ground(true);
    const Scene glow = glowing(plain);
    const RslSet lights = test::random_rsls(8, 3);
    const PinholeCamera camera = PinholeCamera::at_time(glow.camera, 0.0f, 80, 60);
    const PosedScene posed(glow, 0.0f);
    SECTION("vertex colours' blend") {
        CpuRenderer without(plain, lights, {}, per_vertex_options()), with(glow, lights, {}, per_vertex_options());
        const VertexColors reflected = without.shade(), colors = with.shade();
        const Image image = with.form_image(colors, camera);
        int ground = 0, detail = 0;
        for (int y = 0; y < camera.height; ++y)
            for (int x = 0; x < camera.width; ++x) {
                const RayHit hit = pixel_hit(posed, camera, x, y);
                if (!hit.hit) continue;
                const size_t p = size_t(hit.instance);
                const TriangleMesh& mesh = glow.parts[p].mesh;
                const Vec2 uv = mesh.texcoords.empty() ? Vec2(0) : interpolate_texcoords(glow, hit);
                // What the surface reflects, formed as without emission, plus the emission at the pixel.
                const Color reflected_part =
                    reflected.layered(p) ? interpolate_layered_colors(plain, reflected, *layer_texture(plain, reflected, p), hit)
                                         : interpolate_vertex_colors(plain, reflected, hit);
                const Color expected = reflected_part + expected_emission(glow, p, uv);
                const float* pixel = image.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    INFO("pixel " << x << ", " << y << " channel " << c);
                    REQUIRE(pixel[c] == Approx(expected[c]).epsilon(1e-5).margin(1e-6));
                }
                if (p != 0) continue;  // the ground
                ++ground;
                // The texture's own detail, which the vertices' blend of it would lose.
                const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
                const Color blend = (1.0f - hit.u - hit.v) * expected_emission(glow, 0, mesh.texcoords[tri[0]]) +
                                    hit.u * expected_emission(glow, 0, mesh.texcoords[tri[1]]) +
                                    hit.v * expected_emission(glow, 0, mesh.texcoords[tri[2]]);
                if (glm::length(blend - expected_emission(glow, 0, uv)) > 0.05f) ++detail;
            }
        INFO(ground << " ground pixels, " << detail << " where the blend would be off by more than 0.05");
        CHECK(ground > camera.width * camera.height / 4);
        CHECK(detail > ground / 20);  // measured 11%
    }
    SECTION("the parts shaded per pixel add it too") {
        // The ground is a rectangle: shaded per pixel (pixel_shadows planes).
        CpuRenderer without(plain, lights, {}, RenderOptions{}), with(glow, lights, {}, RenderOptions{});
        without.keep_image_terms(true);
        with.keep_image_terms(true);
        const Image a = with.form_image(with.shade(), camera), b = without.form_image(without.shade(), camera);
        int compared = 0;
        for (int y = 0; y < camera.height; ++y)
            for (int x = 0; x < camera.width; ++x) {
                const RayHit hit = pixel_hit(posed, camera, x, y);
                if (!hit.hit) continue;
                const size_t p = size_t(hit.instance);
                const Vec2 uv = glow.parts[p].mesh.texcoords.empty() ? Vec2(0) : interpolate_texcoords(glow, hit);
                const Color expected = expected_emission(glow, p, uv);
                for (int c = 0; c < 3; ++c) {
                    INFO("pixel " << x << ", " << y << " channel " << c);
                    REQUIRE(a.at(x, y)[c] - b.at(x, y)[c] == Approx(expected[c]).epsilon(1e-4).margin(1e-5));
                }
                ++compared;
            }
        CHECK(compared > camera.width * camera.height / 4);
    }
}

TEST_CASE("The truth adds the same emission, per vertex and per pixel", "[render][emission][truth]") {
    const Scene plain = test::box_over_coarse_ground(true);
    const Scene glow = glowing(plain);
    const CubeMap sky = test::sky_with_sun(8);
    const GroundTruth without(plain, sky, 0.0f), with(glow, sky, 0.0f);
    check_vertex_emission(glow, with.shade_vertices(), without.shade_vertices());
    const PinholeCamera camera = PinholeCamera::at_time(glow.camera, 0.0f, 24, 18);
    const PosedScene& posed = with.posed();
    int compared = 0;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const Vec3 direction = camera.direction(float(x) + 0.5f, float(y) + 0.5f);
            const RayHit hit = posed.rays().intersect(camera.eye, direction);
            if (!hit.hit) continue;
            const size_t p = size_t(hit.instance);
            const Vec2 uv = glow.parts[p].mesh.texcoords.empty() ? Vec2(0) : interpolate_texcoords(glow, hit);
            const Color added = with.shade_hit(hit, direction) - without.shade_hit(hit, direction);
            const Color expected = expected_emission(glow, p, uv);
            for (int c = 0; c < 3; ++c) REQUIRE(added[c] == Approx(expected[c]).epsilon(1e-5).margin(1e-6));
            ++compared;
        }
    CHECK(compared > 100);
}

}  // namespace
}  // namespace rsl
