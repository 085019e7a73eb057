// The renderer's sum against hand-computed products (one part, one light),
// and its invariance under a rotation of everything.
#include <catch2/catch.hpp>

#include <random>

#include "src/image/error_metrics.h"
#include "src/render/cpu_renderer.h"
#include "src/trace/ground_truth.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

using test::add_part;
using test::make_plane;
using test::make_scene;

// The plane's vertex frame (make_plane: normal +Y, tangent +X): x = +X,
// y = n × t = −Z, z = +Y.
Vec3 plane_local(const Vec3& w) { return Vec3(w.x, -w.z, w.y); }

// Returns 0.5 + 0.4·light.x + 0.05·point.y in its own frame: a field whose
// value shows whether point and light were moved into the occluder's frame.
class LinearTestField final : public OccluderField {
public:
    float visible_fraction(const Vec3& point, const Vec3& light, float) const override {
        return 0.5f + 0.4f * light.x + 0.05f * point.y;
    }
    BoundingSphere reach() const override { return BoundingSphere{Vec3(0), 1e6f}; }
};

TEST_CASE("one part, one RSL: 2r²·I × BRDF average × SVDF average", "[render]") {
    const Color albedo(0.8f, 0.6f, 0.4f);
    Scene scene = make_scene("hand", albedo);
    add_part(scene, make_plane(2.0f, 4));
    const Vec3 center = glm::normalize(Vec3(0.3f, 1.0f, 0.2f));
    const float r = 0.3f;
    const Color radiance(2.0f, 1.0f, 0.5f);

    // Expected: the square of half-edge r/2 centered at p(c) in the local
    // plane; for Lambert ρ·cos = albedo/π · (1 − |p|²).
    const Vec3 local = plane_local(center);
    const Vec2 p = hemisphere_to_plane(local);
    const float h = 0.5f * r;
    const Color unshadowed = 2.0f * r * r * radiance * albedo * kInvPi * test::square_average_cosine(p, h);

    SECTION("without visibility") {
        PartFields fields;
        CpuRenderer renderer(scene, test::single_rsl(center, r, radiance), fields, RenderOptions{});
        const VertexColors colors = renderer.shade();
        REQUIRE(renderer.stats().lookups == scene.parts[0].mesh.vertex_count());
        for (const Color& c : colors.parts[0])
            for (int ch = 0; ch < 3; ++ch) CHECK(c[ch] == Approx(unshadowed[ch]).epsilon(2e-3));
    }
    SECTION("with a self-visibility field of visible fraction 0.3") {
        PartFields fields;
        fields.self = {test::constant_svdf(int(scene.parts[0].mesh.vertex_count()), -0.4f * h)};
        CpuRenderer renderer(scene, test::single_rsl(center, r, radiance), fields, RenderOptions{});
        const VertexColors colors = renderer.shade();
        for (const Color& c : colors.parts[0])
            for (int ch = 0; ch < 3; ++ch) CHECK(c[ch] == Approx(0.3f * unshadowed[ch]).epsilon(2e-3));

        RenderOptions no_self;
        no_self.self_visibility = false;
        CpuRenderer off(scene, test::single_rsl(center, r, radiance), fields, no_self);
        const VertexColors off_colors = off.shade();
        for (const Color& c : off_colors.parts[0]) CHECK(c.r == Approx(unshadowed.r).epsilon(2e-3));
    }
    SECTION("with an occluder: point and light in the occluder's frame") {
        // The occluder: centered below, turned 90° about Z, so that its frame
        // maps world (x, y, z) to (y, −x, z) after removing its translation.
        // Its mesh (a sphere of radius 20) only sets its bounding box, which
        // holds the receiver, so that the slab rule (square_lights.h) leaves
        // the test field's factor alone.
        Transform pose;
        pose.translation = Vec3(0, -5, 0);
        pose.rotation = glm::angleAxis(0.5f * kPi, Vec3(0, 0, 1));
        add_part(scene, test::make_icosphere(20.0f, 1, "occluder"), pose);
        PartFields fields;
        fields.occluder = {nullptr, std::make_shared<LinearTestField>()};
        RenderOptions options;
        options.occluder_culling = false;
        CpuRenderer renderer(scene, test::single_rsl(center, r, radiance), fields, options);
        const VertexColors colors = renderer.shade();
        const TriangleMesh& mesh = scene.parts[0].mesh;
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            // light.x = world y; point.y = −(world x).
            const float factor = 0.5f + 0.4f * center.y - 0.05f * mesh.positions[v].x;
            for (int ch = 0; ch < 3; ++ch)
                CHECK(colors.parts[0][v][ch] == Approx(factor * unshadowed[ch]).epsilon(2e-3));
        }
        RenderOptions no_occluders = options;
        no_occluders.occluders = false;
        CpuRenderer off(scene, test::single_rsl(center, r, radiance), fields, no_occluders);
        CHECK(off.shade().parts[0][0].g == Approx(unshadowed.g).epsilon(2e-3));
    }
}

TEST_CASE("a sphere light is a per-vertex square of the cap's solid angle", "[render]") {
    const Color albedo(0.5f);
    Scene scene = make_scene("local", albedo);
    add_part(scene, make_plane(2.0f, 4));
    LocalLight light;
    light.radius = 0.1f;
    light.power = Color(3.0f, 2.0f, 1.0f);
    light.position = Vec3(0.3f, 0.8f, -0.2f);
    scene.lights.push_back(light);
    PartFields fields;
    CpuRenderer renderer(scene, RslSet{}, fields, RenderOptions{});
    const VertexColors colors = renderer.shade();
    const Color radiance = light.power / (4.0f * kPi * kPi * light.radius * light.radius);
    const TriangleMesh& mesh = scene.parts[0].mesh;
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Vec3 to_light = light.position - mesh.positions[v];
        const float d = glm::length(to_light);
        const float cos_alpha = std::sqrt(1.0f - light.radius * light.radius / (d * d));
        const float solid_angle = 2.0f * kPi * (1.0f - cos_alpha);
        const float h = 0.5f * std::sqrt(0.5f * solid_angle);
        const Vec2 p = hemisphere_to_plane(plane_local(to_light / d));
        const Color scale = solid_angle * radiance * albedo * kInvPi;
        const Color expected = scale * test::square_average_cosine(p, h);
        // The table is piecewise constant over texels of side 2/N; a square of
        // about one texel (as here) can be off by the cosine's change over half
        // a texel, |∇(1 − |p|²)|·(1/N) = 2|p|/N, plus float rounding.
        const float cosine_tolerance = 2.0f * glm::length(p) / 32.0f + 1e-4f;
        for (int ch = 0; ch < 3; ++ch)
            CHECK(colors.parts[0][v][ch] == Approx(expected[ch]).margin(scale[ch] * cosine_tolerance));
    }
}

TEST_CASE("a spot light's cone: the renderer's per-vertex sum against the ground truth", "[render]") {
    // A spot 1 above a ground plane, pointing down: lit inside 0.3 rad, dark
    // beyond 0.6 rad (radii 0.31 and 0.68 on the ground), glTF's falloff between.
    Scene scene = make_scene("spot", Color(0.5f));
    add_part(scene, make_plane(3.0f, 48));
    LocalLight spot;
    spot.radius = 0.02f;
    spot.power = Color(3.0f, 2.0f, 1.0f);
    spot.position = Vec3(0.1f, 1.0f, -0.05f);
    spot.axis = glm::normalize(Vec3(0.2f, -1.0f, 0.1f));
    spot.spot = true;
    spot.inner_cone_radians = 0.3f;
    spot.outer_cone_radians = 0.6f;
    scene.lights.push_back(spot);
    PartFields fields;
    GroundTruthOptions options;
    options.environment = false;
    const VertexColors rendered = CpuRenderer(scene, RslSet{}, fields, RenderOptions{}).shade();
    const VertexColors truth = GroundTruth(scene, CubeMap(4), 0.0f, options).shade_vertices();
    // The same light without its cone.
    Scene point_scene = scene;
    point_scene.lights[0].spot = false;
    const VertexColors rendered_point = CpuRenderer(point_scene, RslSet{}, fields, RenderOptions{}).shade();
    const VertexColors truth_point = GroundTruth(point_scene, CubeMap(4), 0.0f, options).shade_vertices();

    const TriangleMesh& mesh = scene.parts[0].mesh;
    size_t dark = 0, full = 0, edge = 0;
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Vec3 w = glm::normalize(mesh.positions[v] - spot.position);
        const float angle = std::acos(glm::dot(w, spot.axis));
        // KHR_lights_punctual's reference falloff, independently of the shading core.
        const float f = std::clamp((std::cos(angle) - std::cos(0.6f)) / (std::cos(0.3f) - std::cos(0.6f)), 0.0f, 1.0f);
        const float cone = f * f;
        const Color t = truth.parts[0][v], r = rendered.parts[0][v];
        INFO("vertex " << v << " at " << angle << " rad: truth " << t.g << ", rendered " << r.g << ", cone " << cone
                       << ", as a point light: truth " << truth_point.parts[0][v].g << ", rendered "
                       << rendered_point.parts[0][v].g);
        dark += angle > 0.6f;
        full += angle < 0.3f;
        edge += angle >= 0.3f && angle <= 0.6f;
        // Both scale the point light's per-vertex value by the cone, the truth
        // its exact integral, the renderer its square-light sum.
        for (int c = 0; c < 3; ++c) {
            // (margin: float rounding of cos θ, ~1e-7, where the cone is nearly 0)
            CHECK(t[c] == Approx(cone * truth_point.parts[0][v][c]).epsilon(1e-4).margin(1e-6 * truth_point.parts[0][v][c]));
            CHECK(r[c] == Approx(cone * rendered_point.parts[0][v][c]).epsilon(1e-4).margin(1e-6 * rendered_point.parts[0][v][c]));
        }
    }
    CHECK(dark > 1000);
    CHECK(full > 50);
    CHECK(edge > 200);
    // And the renderer against the truth: the square-light error of the point
    // light (the BRDF table's texels, docs/design/RENDERER.md), no more.
    const double error = compare_vertex_colors(rendered, truth).total.relative_l2();
    const double point_error = compare_vertex_colors(rendered_point, truth_point).total.relative_l2();
    INFO("relative L2: spot " << error << ", point " << point_error);
    CHECK(error < 0.01);
    CHECK(error < 1.5 * point_error);
    CHECK(compare_vertex_colors(rendered_point, truth).total.relative_l2() > 0.3);  // the cone matters
}

// A small scene with real baked fields: a ground plane, two spheres (one
// glossy), a few RSLs and a sphere light.
Scene fields_scene() {
    Scene scene = make_scene("fields", Color(0.7f));
    scene.materials.push_back(test::blinn_phong(0.4f, 0.3f, 30.0f));
    add_part(scene, make_plane(3.0f, 12, "ground"));
    Transform big, small;
    big.translation = Vec3(0, 0.45f, 0);
    small.translation = Vec3(0.55f, 0.25f, 0.2f);
    add_part(scene, test::make_icosphere(0.4f, 2, "big"), big, 1);
    add_part(scene, test::make_icosphere(0.2f, 2, "small"), small, 0);
    scene.camera.position = Vec3(1.2f, 1.6f, 2.5f);
    scene.camera.target = Vec3(0, 0.3f, 0);
    LocalLight light;
    light.radius = 0.05f;
    light.power = Color(2.0f);
    light.position = Vec3(-0.6f, 1.2f, 0.4f);
    scene.lights.push_back(light);
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 16, pre.svdf_clusters = 8, pre.svdf_vectors = 4, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 4, pre.ovdf_cube_resolution = 8, pre.ovdf_vdt_resolution = 16, pre.ovdf_vectors = 4;
    return scene;
}

// Puts every top-level node under a new root with the given rotation.
void rotate_scene(Scene& scene, const Quat& rotation) {
    SceneNode root;
    root.name = "root";
    root.rest.rotation = rotation;
    scene.nodes.push_back(root);
    const int root_index = int(scene.nodes.size()) - 1;
    for (int n = 0; n < root_index; ++n)
        if (scene.nodes[n].parent < 0) scene.nodes[n].parent = root_index;
    const Mat3 m = glm::mat3_cast(rotation);
    scene.camera.position = m * scene.camera.position;
    scene.camera.target = m * scene.camera.target;
    scene.camera.up = m * scene.camera.up;
    for (LocalLight& light : scene.lights) light.position = m * light.position;
}

TEST_CASE("rotating the environment by R equals rotating the scene by R⁻¹", "[render]") {
    const Scene scene = fields_scene();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = test::random_rsls(12, 7, 0.1f);
    RenderOptions options;
    options.occluder_culling = false;  // the same lookups both ways

    // A: the environment turned by R, the scene as it is.
    const Vec3 axis = glm::normalize(Vec3(0.3f, 0.8f, -0.5f));
    const float degrees = 67.0f;
    Scene turned_environment = scene;
    turned_environment.environment.rotation_axis = axis;
    turned_environment.environment.rotation_degrees = degrees;
    CpuRenderer a(turned_environment, lights, fields, options);
    const VertexColors expected = a.shade();

    // B: the environment as it is, the scene (parts, camera, lights) turned by R⁻¹.
    Scene turned_scene = scene;
    rotate_scene(turned_scene, glm::angleAxis(glm::radians(-degrees), axis));
    CpuRenderer b(turned_scene, lights, fields, options);
    const VertexColors colors = b.shade();

    // Every lookup sees the same local coordinates up to the float rounding of
    // the rotated frames (~1e-6 plane units), so colours agree to ~1e-5 — except
    // where a receiver sits exactly on an OVDF cube-face seam as seen from an
    // occluder: rounding can pick the other face, whose samples interpolate to
    // a slightly different value (measured: one vertex of 493, 1.4%).
    double error2 = 0, norm2 = 0;
    size_t vertices = 0, differing = 0;
    for (size_t p = 0; p < expected.parts.size(); ++p)
        for (size_t v = 0; v < expected.parts[p].size(); ++v) {
            const Vec3 d = colors.parts[p][v] - expected.parts[p][v];
            error2 += glm::dot(d, d);
            norm2 += glm::dot(expected.parts[p][v], expected.parts[p][v]);
            ++vertices;
            if (glm::length(d) > 1e-4f * glm::length(expected.parts[p][v]) + 1e-7f) ++differing;
        }
    INFO("relative L2 difference " << std::sqrt(error2 / norm2) << ", " << differing << " of " << vertices
                                   << " vertices differ by more than 1e-4");
    REQUIRE(norm2 > 0);
    CHECK(differing <= vertices / 100);
    CHECK(std::sqrt(error2 / norm2) < 3e-3);
    // Without the occluder fields nothing is discontinuous: float noise only.
    RenderOptions self_only = options;
    self_only.occluders = false;
    CpuRenderer a_self(turned_environment, lights, fields, self_only), b_self(turned_scene, lights, fields, self_only);
    const VertexColors ea = a_self.shade(), eb = b_self.shade();
    double self_error2 = 0, self_norm2 = 0;
    for (size_t p = 0; p < ea.parts.size(); ++p)
        for (size_t v = 0; v < ea.parts[p].size(); ++v) {
            const Vec3 d = eb.parts[p][v] - ea.parts[p][v];
            self_error2 += glm::dot(d, d);
            self_norm2 += glm::dot(ea.parts[p][v], ea.parts[p][v]);
        }
    CHECK(std::sqrt(self_error2 / self_norm2) < 1e-5);
    // And the fields do matter: switching them off changes the colours.
    RenderOptions no_visibility = options;
    no_visibility.self_visibility = no_visibility.occluders = false;
    CpuRenderer bare(turned_environment, lights, fields, no_visibility);
    const VertexColors unshadowed = bare.shade();
    double change2 = 0;
    for (size_t p = 0; p < expected.parts.size(); ++p)
        for (size_t v = 0; v < expected.parts[p].size(); ++v) {
            const Vec3 d = unshadowed.parts[p][v] - expected.parts[p][v];
            change2 += glm::dot(d, d);
        }
    CHECK(std::sqrt(change2 / norm2) > 0.05);
}

}  // namespace
}  // namespace rsl
