// The ground truth against analytic answers: the furnace, a square area light
// (polygon form factor), a sphere's shadow from a small source, moving parts,
// a spherical local light, and the per-pixel truth of a wall on a floor.
#include <atomic>
#include <cmath>

#include <catch2/catch.hpp>

#include "src/image/image_formation.h"
#include "src/trace/ground_truth.h"
#include "tests/trace/trace_test_scenes.h"

using namespace rsl;

namespace {

constexpr int kFaceTop = 2;  // +Y in OpenGL face order

// ∫ cos θ dω over the spherical polygon with unit corner directions `corners`
// (great-circle edges), seen from a surface with unit normal n, the polygon
// wholly above the horizon: Lambert's formula ½ Σ_i Θ_i (n · û_i).
double polygon_cosine_integral(const std::vector<DVec3>& corners, DVec3 n) {
    double sum = 0;
    for (size_t i = 0; i < corners.size(); ++i) {
        const DVec3 a = glm::normalize(corners[i]), b = glm::normalize(corners[(i + 1) % corners.size()]);
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
    }
    return 0.5 * std::abs(sum);
}

// The directions through the corners of texels [i0, i1) × [j0, j1) of a face, rotated.
std::vector<DVec3> block_corners(int n, int face, int i0, int i1, int j0, int j1, const Mat3& rotation) {
    auto coord = [n](int i) { return -1.0f + 2.0f * float(i) / float(n); };
    std::vector<DVec3> corners;
    for (auto [i, j] : {std::pair{i0, j0}, {i1, j0}, {i1, j1}, {i0, j1}})
        corners.push_back(DVec3(rotation * CubeMap::face_direction(face, coord(i), coord(j))));
    return corners;
}

SurfacePoint point_on_floor(Vec3 p) {
    SurfacePoint x;
    x.position = p;
    x.frame = Frame::from_normal_tangent(Vec3(0, 1, 0), Vec3(1, 0, 0));
    x.offset_normal = x.frame.z;
    return x;
}

// Does the ray o + s d (s > 0) meet the sphere (c, r)?
bool ray_meets_sphere(DVec3 o, DVec3 d, DVec3 c, double r) {
    const DVec3 oc = c - o;
    const double b = glm::dot(oc, d);
    return b > 0 && glm::dot(oc, oc) - b * b < r * r;
}

// A 6 × 6 floor (albedo 1) under a sphere of `radius` at `center`.
Scene sphere_over_floor(const std::string& name, Vec3 center, float radius, int subdivisions) {
    Scene scene = test::make_scene(name);
    test::add_part(scene, test::make_plane(6.0f, 2));
    Transform at;
    at.translation = center;
    test::add_part(scene, test::make_icosphere(radius, subdivisions), at);
    return scene;
}

// The cosine-weighted fraction of the top-face block [i0, i1)² of an n×n
// face that a floor point p sees past the sphere (center, radius): 1024²
// samples over the block in face coordinates, exact sphere, no Embree.
double lit_fraction_of_top_block(Vec3 p, int n, int i0, int i1, Vec3 center, float radius) {
    const int m = 1024;
    const double s0 = -1.0 + 2.0 * i0 / n, s1 = -1.0 + 2.0 * i1 / n;
    double lit = 0, all = 0;
    for (int b = 0; b < m; ++b)
        for (int a = 0; a < m; ++a) {
            const double s = s0 + (s1 - s0) * (a + 0.5) / m, t = s0 + (s1 - s0) * (b + 0.5) / m;
            const DVec3 d = glm::normalize(DVec3(s, 1.0, t));
            const double weight = d.y / std::pow(s * s + 1.0 + t * t, 1.5);  // cos · dω/ds dt
            all += weight;
            if (!ray_meets_sphere(DVec3(p), d, DVec3(center), radius)) lit += weight;
        }
    return lit / all;
}

}  // namespace

TEST_CASE("Furnace: white unit environment, albedo 1, no occluders gives 1 at every vertex", "[trace][truth]") {
    SECTION("a horizontal plane, one ray per texel") {
        Scene scene = test::make_scene("furnace");
        test::add_part(scene, test::make_plane(2.0f, 8));
        const GroundTruth truth(scene, test::constant_cube(32, Color(1)), 0.0f);
        const VertexColors b = truth.shade_vertices();
        REQUIRE(b.vertex_count() == 81);
        for (const Color& c : b.parts[0]) {
            REQUIRE(c.r == Approx(1.0f).margin(1e-3));
            REQUIRE(c.g == Approx(1.0f).margin(1e-3));
            REQUIRE(c.b == Approx(1.0f).margin(1e-3));
        }
    }
    SECTION("a tilted plane: the horizon cuts texels, a 4×4 sub-grid per texel") {
        Scene scene = test::make_scene("furnace-tilted");
        Transform tilt;
        tilt.rotation = glm::angleAxis(glm::radians(33.0f), glm::normalize(Vec3(1, 0.2f, 1)));
        test::add_part(scene, test::make_plane(2.0f, 4), tilt);
        scene.camera.position = Vec3(tilt.matrix() * Vec4(0, 10, 0.5f, 1));
        GroundTruthOptions options;
        options.texel_subdivision = 4;
        const GroundTruth truth(scene, test::constant_cube(32, Color(1)), 0.0f, options);
        const VertexColors b = truth.shade_vertices();
        for (const Color& c : b.parts[0]) REQUIRE(c.g == Approx(1.0f).margin(1e-3));
    }
}

TEST_CASE("Square area light: a plane's radiance equals the polygon form factor", "[trace][truth]") {
    const int n = 32;
    const Color radiance(2.0f, 3.0f, 5.0f);
    // A 6×4-texel block off the zenith, the environment turned about a tilted axis.
    const int i0 = 5, i1 = 11, j0 = 18, j1 = 22;
    for (float degrees : {0.0f, 25.0f, 50.0f}) {
        Scene scene = test::make_scene("area-light", Color(0.5f, 0.8f, 1.0f));
        test::add_part(scene, test::make_plane(2.0f, 2));
        scene.environment.rotation_axis = Vec3(1, 0, 0.3f);
        scene.environment.rotation_degrees = degrees;
        const GroundTruth truth(scene, test::block_cube(n, kFaceTop, i0, i1, j0, j1, radiance), 0.0f);
        const Mat3 rotation = scene.environment.rotation_at(0.0f);
        const std::vector<DVec3> corners = block_corners(n, kFaceTop, i0, i1, j0, j1, rotation);
        for (const DVec3& corner : corners) REQUIRE(corner.y > 0.0);  // the formula needs it above the horizon
        const double form_factor = polygon_cosine_integral(corners, DVec3(0, 1, 0)) / kPi;
        INFO("rotation " << degrees << "°, form factor " << form_factor);
        REQUIRE(form_factor > 0.003);
        const VertexColors b = truth.shade_vertices();
        for (const Color& c : b.parts[0]) {
            REQUIRE(c.r / (0.5 * radiance.r * form_factor) == Approx(1.0).margin(1e-3));
            REQUIRE(c.g / (0.8 * radiance.g * form_factor) == Approx(1.0).margin(1e-3));
            REQUIRE(c.b / (1.0 * radiance.b * form_factor) == Approx(1.0).margin(1e-3));
        }
    }
}

TEST_CASE("A sphere's shadow from a small source has the analytic shadowed fraction", "[trace][truth]") {
    const int n = 32, i0 = 14, i1 = 18;  // a 4×4-texel source at the zenith (about 14° wide)
    const Vec3 center(0, 1.5f, 0);
    const float radius = 0.5f;
    const Scene scene = sphere_over_floor("sphere-shadow", center, radius, 5);
    GroundTruthOptions options;
    options.texel_subdivision = 16;
    const GroundTruth truth(scene, test::block_cube(n, kFaceTop, i0, i1, i0, i1, Color(100)), 0.0f, options);
    const double unshadowed = 100.0 / kPi *
        polygon_cosine_integral(block_corners(n, kFaceTop, i0, i1, i0, i1, Mat3(1.0f)), DVec3(0, 1, 0));

    for (Vec3 p : {Vec3(0, 0, 0), Vec3(0.3f, 0, 0), Vec3(0.4f, 0, 0), Vec3(0.5f, 0, 0), Vec3(0.6f, 0, 0),
                   Vec3(0.35f, 0, 0.35f), Vec3(0.7f, 0, 0), Vec3(1.2f, 0, 0)}) {
        const double reference = lit_fraction_of_top_block(p, n, i0, i1, center, radius);
        const double measured = luminance(truth.shade(point_on_floor(p), Vec3(0, 1, 0), truth.part_brdf(0))) /
                                luminance(Color(float(unshadowed)));
        INFO("point " << p.x << ", " << p.z << ": reference " << reference << ", truth " << measured);
        REQUIRE(measured == Approx(reference).margin(3e-3));
    }
}

TEST_CASE("A one-texel sun casts the penumbra of its texel, not the hard shadow of its centre", "[trace][truth]") {
    // The map is piecewise constant: the truth's integral of a bright texel
    // has a penumbra as wide as the texel (about 3.6° here), which one ray
    // through its centre would miss; bright texels are cut finer.
    const int n = 32, i0 = 16, i1 = 17;
    const Vec3 center(0, 1.5f, 0);
    const float radius = 0.5f;
    const Scene scene = sphere_over_floor("sun-penumbra", center, radius, 6);
    const CubeMap sun = test::block_cube(n, kFaceTop, i0, i1, i0, i1, Color(1000));
    const double unshadowed = 1000.0 / kPi *
        polygon_cosine_integral(block_corners(n, kFaceTop, i0, i1, i0, i1, Mat3(1.0f)), DVec3(0, 1, 0));
    GroundTruthOptions one_ray;
    one_ray.max_sample_share = 0.0f;
    const GroundTruth truth(scene, sun, 0.0f), centre_only(scene, sun, 0.0f, one_ray);
    REQUIRE(truth.environment_sample_count() ==
            size_t(GroundTruthOptions::kMaxAdaptiveSubdivision * GroundTruthOptions::kMaxAdaptiveSubdivision));
    REQUIRE(centre_only.environment_sample_count() == 1);
    double worst_centre_only = 0;
    int penumbra = 0;
    for (float x = 0.46f; x <= 0.62f; x += 0.01f) {
        const Vec3 p(x, 0, 0.02f);
        const double reference = lit_fraction_of_top_block(p, n, i0, i1, center, radius);
        const double measured =
            luminance(truth.shade(point_on_floor(p), Vec3(0, 1, 0), truth.part_brdf(0))) / unshadowed;
        const double centre =
            luminance(centre_only.shade(point_on_floor(p), Vec3(0, 1, 0), centre_only.part_brdf(0))) / unshadowed;
        INFO("x " << x << ": reference " << reference << ", truth " << measured << ", one ray " << centre);
        REQUIRE(measured == Approx(reference).margin(1e-2));
        worst_centre_only = std::max(worst_centre_only, std::abs(centre - reference));
        if (reference > 0.05 && reference < 0.95) ++penumbra;
    }
    REQUIRE(penumbra >= 4);              // the points cross the penumbra
    REQUIRE(worst_centre_only > 0.25);   // where one ray a texel is wrong
}

TEST_CASE("Without shadows the truth is the unshadowed integral", "[trace][truth]") {
    const int n = 32, i0 = 14, i1 = 18;
    const Scene scene = sphere_over_floor("unshadowed", Vec3(0, 1.5f, 0), 0.5f, 3);
    const CubeMap source = test::block_cube(n, kFaceTop, i0, i1, i0, i1, Color(100));
    GroundTruthOptions options;
    options.shadows = false;
    const GroundTruth shadowed(scene, source, 0.0f), unshadowed(scene, source, 0.0f, options);
    const double expected = 100.0 / kPi *
        polygon_cosine_integral(block_corners(n, kFaceTop, i0, i1, i0, i1, Mat3(1.0f)), DVec3(0, 1, 0));
    const SurfacePoint under = point_on_floor(Vec3(0));
    REQUIRE(luminance(shadowed.shade(under, Vec3(0, 1, 0), shadowed.part_brdf(0))) == 0.0f);
    REQUIRE(luminance(unshadowed.shade(under, Vec3(0, 1, 0), unshadowed.part_brdf(0))) ==
            Approx(expected).epsilon(2e-3));
}

TEST_CASE("Moving a part moves its shadow without rebuilding the scene", "[trace][truth]") {
    Scene scene = test::make_scene("moving");
    test::add_part(scene, test::make_plane(6.0f, 12));
    Transform at;
    at.translation = Vec3(0, 1.5f, 0);
    const int sphere = test::add_part(scene, test::make_icosphere(0.5f, 3), at);
    Vec3Track track;
    track.times = {0.0f, 1.0f};
    track.values = {Vec3(0, 1.5f, 0), Vec3(1.5f, 1.5f, 0)};
    scene.nodes[scene.parts[sphere].node].translation = track;
    const CubeMap sun = test::block_cube(16, kFaceTop, 7, 9, 7, 9, Color(50));

    GroundTruth truth(scene, sun, 0.0f);
    const SurfacePoint under_start = point_on_floor(Vec3(0)), under_end = point_on_floor(Vec3(1.5f, 0, 0));
    const Vec3 up(0, 1, 0);
    const Brdf& brdf = truth.part_brdf(0);
    const float lit = luminance(truth.shade(point_on_floor(Vec3(-2.5f, 0, 0)), up, brdf));
    REQUIRE(lit > 0.0f);
    REQUIRE(luminance(truth.shade(under_start, up, brdf)) == 0.0f);
    REQUIRE(luminance(truth.shade(under_end, up, brdf)) == Approx(lit).epsilon(1e-5));

    truth.set_time(1.0f);
    REQUIRE(luminance(truth.shade(under_start, up, brdf)) == Approx(lit).epsilon(1e-5));
    REQUIRE(luminance(truth.shade(under_end, up, brdf)) == 0.0f);

    // The same as a scene built from scratch at t = 1.
    const GroundTruth fresh(scene, sun, 1.0f);
    const VertexColors moved = truth.shade_vertices(), built = fresh.shade_vertices();
    REQUIRE(moved.time == 1.0f);
    size_t shadowed = 0;
    for (size_t p = 0; p < moved.parts.size(); ++p)
        for (size_t v = 0; v < moved.parts[p].size(); ++v) {
            REQUIRE(moved.parts[p][v].g == Approx(built.parts[p][v].g).margin(1e-6));
            if (p == 0 && moved.parts[p][v].g == 0.0f) ++shadowed;
        }
    REQUIRE(shadowed > 0);
}

TEST_CASE("A sphere light matches the irradiance of a spherical source", "[trace][truth]") {
    const float a = 0.2f;
    Scene scene = test::make_scene("sphere-light", Color(0.9f));
    test::add_part(scene, test::make_plane(4.0f, 2));
    LocalLight light;
    light.radius = a;
    light.power = Color(10, 20, 30);
    light.position = Vec3(0, 1, 0);
    scene.lights.push_back(light);
    const GroundTruth truth(scene, CubeMap(4), 0.0f);
    const Color radiance = light.power / (4.0f * kPi * kPi * a * a);
    REQUIRE(sphere_light_radiance(light).g == Approx(radiance.g));

    for (Vec3 p : {Vec3(0), Vec3(0.8f, 0, 0), Vec3(-0.5f, 0, 1.1f), Vec3(1.6f, 0, 0.2f)}) {
        // E = π L sin²α cos θ for a sphere wholly above the horizon; B = (albedo/π) E.
        const Vec3 to_light = light.position - p;
        const float d = glm::length(to_light);
        const float cos_theta = to_light.y / d;
        REQUIRE(std::acos(cos_theta) + std::asin(a / d) < 0.5f * kPi);
        const Color expected = 0.9f * radiance * (a * a / (d * d)) * cos_theta;
        const Color b = truth.shade(point_on_floor(p), Vec3(0, 1, 0), truth.part_brdf(0));
        INFO("point " << p.x << ", " << p.z);
        REQUIRE(b.r == Approx(expected.r).epsilon(1e-3));
        REQUIRE(b.b == Approx(expected.b).epsilon(1e-3));
    }

    // A sphere between the light and the floor hides it completely.
    Transform at;
    at.translation = Vec3(0, 0.5f, 0);
    test::add_part(scene, test::make_icosphere(0.3f, 3), at);
    const GroundTruth blocked(scene, CubeMap(4), 0.0f);
    REQUIRE(luminance(blocked.shade(point_on_floor(Vec3(0)), Vec3(0, 1, 0), blocked.part_brdf(0))) == 0.0f);
    REQUIRE(luminance(blocked.shade(point_on_floor(Vec3(1.6f, 0, 0.2f)), Vec3(0, 1, 0), blocked.part_brdf(0))) > 0.0f);
}

namespace {

// A unit box (flat-shaded, 2 × 2 quads a face) centred at `center` on an
// 8 m ground of `ground_cells`² cells, under a camera that sees the box's
// +X and +Z faces (the view must be above a face's horizon).
Scene unit_box_on_ground(int ground_cells, const Vec3& center) {
    Scene scene = test::make_scene("box_on_ground", Color(1));
    test::add_part(scene, test::make_plane(8.0f, ground_cells, "ground"));
    Transform pose;
    pose.translation = center;
    test::add_part(scene, test::make_flat_box(Vec3(0.5f), 2, "box"), pose);
    scene.camera.position = Vec3(20, 3, 20);
    return scene;
}

// Shades `touching` and `lifted` (the same scene with a gap) under a white
// sky and checks that the vertices of `part` that `selected` picks are lit
// above `at_least` and as in the lifted scene; returns how many it checked.
template <typename Selected>
int check_seam_as_lifted(const Scene& touching, const Scene& lifted, int part, Selected selected, float at_least) {
    const CubeMap sky = test::constant_cube(8, Color(1));
    const VertexColors a = GroundTruth(touching, sky, 0).shade_vertices();
    const VertexColors b = GroundTruth(lifted, sky, 0).shade_vertices();
    const TriangleMesh& mesh = touching.parts[size_t(part)].mesh;
    int checked = 0;
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        if (!selected(mesh.positions[v], mesh.normals[v])) continue;
        ++checked;
        const Vec3 p = mesh.positions[v];
        INFO("part " << part << " vertex " << v << " at " << p.x << ", " << p.y << ", " << p.z << ": touching "
                     << a.parts[part][v].r << ", lifted " << b.parts[part][v].r);
        CHECK(a.parts[part][v].r > at_least);
        CHECK(a.parts[part][v].r == Approx(b.parts[part][v].r).epsilon(0.03));
    }
    return checked;
}

}  // namespace

TEST_CASE("A box standing on the ground: its vertices along the seam are shaded as its faces next to it", "[trace][truth]") {
    // Vertices on the seam lie on the ground's triangles; without the nudge
    // into their own face every ray hits the ground at t = 0 and they come
    // out black (docs/design/TRUTH.md). Reference: the same box lifted by 1e-4,
    // where nothing is degenerate.
    // The box off the ground's grid lines.
    const Scene touching = unit_box_on_ground(8, Vec3(0.05f, 0.5f, 0.1f)),
                lifted = unit_box_on_ground(8, Vec3(0.05f, 0.5f + 1e-4f, 0.1f));
    // The bottom row of the faces the camera sees; a white sky over the
    // upper half of the hemisphere gives 0.5.
    const int seam = check_seam_as_lifted(touching, lifted, 1, [](const Vec3& p, const Vec3& n) {
        return p.y == -0.5f && (n.x > 0.5f || n.z > 0.5f);
    }, 0.4f);
    CHECK(seam == 6);  // 2 faces × 3 vertices
}

TEST_CASE("The ground under a box's edge: its vertices there see the open half, as an instant outside the box",
          "[trace][truth]") {
    // Ground vertices on the line where the box's side faces meet the
    // ground have ground on both sides, so they do not move into their own
    // triangles; their rays start on the box's side plane. Rays leaving the
    // box there are free, rays entering it blocked (RayScene's
    // origins_outside_surfaces), as for the same box lifted by 1e-3: above
    // the rays' origin offset (about 1e-4 here), so nothing is degenerate.
    // Grid lines every 0.25; the box's bottom edges on the lines x, z = 0, 1.
    const Scene touching = unit_box_on_ground(32, Vec3(0.5f, 0.5f, 0.5f)),
                lifted = unit_box_on_ground(32, Vec3(0.5f, 0.5f + 1e-3f, 0.5f));
    // The open half of a white sky, less the box's corner: about 0.5.
    const int edge = check_seam_as_lifted(touching, lifted, 0, [](const Vec3& p, const Vec3&) {
        const bool on_x_edge = (p.x == 0.0f || p.x == 1.0f) && p.z > 0.1f && p.z < 0.9f;
        const bool on_z_edge = (p.z == 0.0f || p.z == 1.0f) && p.x > 0.1f && p.x < 0.9f;
        return on_x_edge || on_z_edge;
    }, 0.3f);
    CHECK(edge == 12);  // 4 edges × 3 inner vertices
}

TEST_CASE("A part's truth does not depend on how large the scene is around it", "[trace][truth]") {
    // One part made of two overlapping boxes, as modelled parts often are:
    // the inner box's top face lies 3e-4 under the outer one's, so its
    // vertices there are inside the part, and every ray from them leaves the
    // outer box (upwards at t = 3e-4, beyond the part's 4 ray offsets,
    // about 1e-4). They are dark, as the part's SVDF bake, which traces the
    // part alone, finds them. A small box 1000 away, which shadows nothing,
    // made the scene's diagonal 1000: with ray offsets scaled by the scene
    // the truth ignored those exits and lit them.
    TriangleMesh part = test::make_flat_box(Vec3(0.5f), 4, "outer");
    const TriangleMesh inner = test::make_flat_box(Vec3(0.3f, 0.5f - 3e-4f, 0.3f), 4, "inner");
    const uint32_t base = uint32_t(part.positions.size());
    part.positions.insert(part.positions.end(), inner.positions.begin(), inner.positions.end());
    part.normals.insert(part.normals.end(), inner.normals.begin(), inner.normals.end());
    part.tangents.insert(part.tangents.end(), inner.tangents.begin(), inner.tangents.end());
    part.texcoords.insert(part.texcoords.end(), inner.texcoords.begin(), inner.texcoords.end());
    for (uint32_t index : inner.indices) part.indices.push_back(base + index);
    const CubeMap sky = test::constant_cube(16, Color(1));
    Scene alone = test::make_scene("alone");
    test::add_part(alone, part);
    Scene with_far = alone;
    Transform far;
    far.translation = Vec3(1000.0f, 0.0f, 0.0f);
    test::add_part(with_far, test::make_flat_box(Vec3(0.01f), 1, "far"), far);
    const VertexColors a = GroundTruth(alone, sky, 0.0f).shade_vertices();
    const VertexColors b = GroundTruth(with_far, sky, 0.0f).shade_vertices();
    int inner_top = 0, lit_inner_top = 0, differ = 0;
    for (size_t v = 0; v < part.vertex_count(); ++v) {
        differ += a.parts[0][v].g == b.parts[0][v].g ? 0 : 1;
        if (v >= base && part.normals[v].y > 0.5f) {
            ++inner_top;
            lit_inner_top += b.parts[0][v].g > 0.0f ? 1 : 0;
        }
    }
    CHECK(inner_top == 25);
    CHECK(lit_inner_top == 0);
    CHECK(differ == 0);
}

TEST_CASE("Per-pixel truth against a known answer: a wall on a floor (a half-space occluder) under a uniform sky",
          "[trace][truth]") {
    // An infinite wall standing on an infinite floor: from any point of
    // either, the other hides exactly the half of its hemisphere that leads
    // into it, and that half holds half of the cosine weight by symmetry.
    // Under a uniform sky L, with direct light only, every Lambertian point
    // of either reflects albedo × L / 2, right up to the seam. A 400 m floor
    // and wall seen within a few metres of their seam stand for the
    // infinite ones (what they leave open lies within 1° of the horizon).
    const float albedo = 0.6f;
    Scene scene = test::make_scene("half_space", Color(albedo));
    test::add_part(scene, test::make_plane(400.0f, 4, "floor"));
    Transform wall;  // the plane's +Y normal turned to −X, its bottom edge on the floor at x = 0
    wall.rotation = glm::angleAxis(glm::radians(90.0f), Vec3(0, 0, 1));
    wall.translation = Vec3(0, 200, 0);
    test::add_part(scene, test::make_plane(400.0f, 4, "wall"), wall);
    scene.camera.position = Vec3(-3.0f, 1.6f, 1.0f);
    scene.camera.target = Vec3(0.0f, 0.4f, 0.0f);
    const GroundTruth truth(scene, test::constant_cube(16, Color(1)), 0.0f);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, 80, 60);
    std::atomic<int> floor_hits{0}, wall_hits{0};  // both must be in view
    const Image image = trace_image(truth.posed(), camera, {}, [&](const RayHit& hit, const Vec3& dir) {
        ++(hit.instance == 0 ? floor_hits : wall_hits);
        return truth.shade_hit(hit, dir);
    });
    int covered = 0, wrong = 0;
    float lowest = 1e9f, highest = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            if (image.at(x, y)[3] < 1.0f) continue;  // the sky, past the floor's far edge
            ++covered;
            const float value = image.at(x, y)[0];
            lowest = std::min(lowest, value), highest = std::max(highest, value);
            if (std::abs(value - 0.5f * albedo) > 0.01f * 0.5f * albedo) ++wrong;
        }
    INFO(covered << " pixels, " << wrong << " off by more than 1%; values " << lowest << " .. " << highest);
    CHECK(covered > image.width * image.height / 2);
    CHECK(floor_hits > covered / 5);
    CHECK(wall_hits > covered / 5);
    CHECK(wrong == 0);
}
