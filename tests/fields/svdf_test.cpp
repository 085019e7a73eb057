#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "src/fields/svdf.h"
#include "src/rays/ray_scene.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

void add_quad(TriangleMesh& mesh, Vec3 origin, Vec3 u, Vec3 v, Vec3 normal, int cells) {
    const uint32_t base = uint32_t(mesh.positions.size());
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            mesh.positions.push_back(origin + u * (float(i) / cells) + v * (float(j) / cells));
            mesh.normals.push_back(normal);
            mesh.tangents.push_back(Vec4(glm::normalize(u), 1));
        }
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const uint32_t a = base + j * (cells + 1) + i, b = a + cells + 1;
            for (uint32_t k : {a, a + 1, b, a + 1, b + 1, b}) mesh.indices.push_back(k);
        }
}

// A 4×4 ground (y = 0, normal +y) with a unit box standing on it.
TriangleMesh plane_with_box() {
    TriangleMesh mesh;
    add_quad(mesh, Vec3(-2, 0, -2), Vec3(0, 0, 4), Vec3(4, 0, 0), Vec3(0, 1, 0), 16);
    const float a = 0.5f;
    add_quad(mesh, Vec3(-a, 1, -a), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), 2);
    add_quad(mesh, Vec3(a, 0, -a), Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0), 2);
    add_quad(mesh, Vec3(-a, 0, -a), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(-1, 0, 0), 2);
    add_quad(mesh, Vec3(-a, 0, a), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), 2);
    add_quad(mesh, Vec3(-a, 0, -a), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), 2);
    return mesh;
}

}  // namespace

TEST_CASE("SVDF of a plane with a box matches ray-traced visible fractions", "[svdf]") {
    const TriangleMesh mesh = plane_with_box();
    SvdfParams params;
    params.vectors = 8;
    SvdfBakeStats stats;
    const Svdf svdf = bake_svdf(mesh, params, &stats);
    REQUIRE(svdf.vertex_count() == int(mesh.vertex_count()));
    std::printf("SVDF plane+box: %d vertices, %d clusters, ratio 1:%.1f, rms %.4f\n", svdf.vertex_count(),
                svdf.model.clusters, stats.compression.compression_ratio(), stats.compression.rms_error);

    // Rays from where the bake and the truth start a vertex's rays: one
    // offset into its own triangles on the border of its surface, origins on
    // the mesh's own surface elsewhere (the box's seam on the plane) outside it.
    RayScene scene(/*origins_outside_surfaces=*/true);
    scene.add_instance(scene.add_mesh(mesh), Mat4(1.0f));
    scene.commit();
    const RayOffset offset{scene.world_diagonal()};
    const std::vector<Vec3> inward = border_inward_directions(mesh);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<double> errors;
    int partial = 0;
    for (int k = 0; k < 600; ++k) {
        const int v = int(u(rng) * 289);  // ground vertices come first
        const Frame frame = vertex_frame(mesh, size_t(v));
        const Vec3 origin = offset.origin(mesh.positions[v], frame.z, inward[size_t(v)]);
        const float h = 0.05f + 0.15f * u(rng);
        const float reach = 0.95f - h * std::sqrt(2.0f);  // keep the square above the horizon
        // Squares around the box's image, so that most straddle its outline.
        const Vec2 towards_box = hemisphere_to_plane(frame.to_local(glm::normalize(Vec3(0, 0.5f, 0) - origin)));
        Vec2 c;
        do c = towards_box + 0.35f * (2.0f * test::random_vec2(u, rng) - 1.0f);
        while (glm::length(c) > reach);
        // Reference: 32×32 rays spread over the square.
        const int m = 32;
        int visible = 0;
        for (int b = 0; b < m; ++b)
            for (int a = 0; a < m; ++a) {
                const Vec2 p = c + h * Vec2(-1 + (2 * a + 1.0f) / m, -1 + (2 * b + 1.0f) / m);
                visible += !scene.occluded(origin, frame.to_world(plane_to_hemisphere(p)), 0.0f, 1e30f);
            }
        const double want = double(visible) / (m * m);
        if (want > 0.02 && want < 0.98) ++partial;
        errors.push_back(std::abs(svdf.visible_fraction(v, c, h) - want));
    }
    std::sort(errors.begin(), errors.end());
    double mean = 0;
    for (double e : errors) mean += e;
    mean /= double(errors.size());
    const double p95 = errors[size_t(0.95 * double(errors.size()))];
    std::printf("SVDF plane+box vs rays: mean %.4f, p95 %.4f over %zu squares (%d in penumbra)\n", mean, p95,
                errors.size(), partial);
    // Measured: mean 0.028, p95 0.108 (GCC 12); mean 0.032, p95 0.128 (clang
    // 14, the sanitizer build; 0.116 before field format 4 changed the box's
    // own tables at its seam, and with them, likely, the shared CPCA
    // clusters) — the VDT
    // rule's error at the box's corners plus CPCA; the same squares read
    // from a boundary off by one texel (0.0625) would be off by
    // 0.0625/(2h) ≥ 0.15.
    CHECK(partial > 200);
    CHECK(mean < 0.04);
    CHECK(p95 < 0.14);
}

TEST_CASE("SVDF direction lookup equals the plane lookup", "[svdf]") {
    const TriangleMesh mesh = plane_with_box();
    SvdfParams params;
    params.supersampling = 1;
    const Svdf svdf = bake_svdf(mesh, params);
    const Vec2 p(0.3f, -0.2f);
    CHECK(svdf.visible_fraction(10, plane_to_hemisphere(p), 0.1f) == Approx(svdf.visible_fraction(10, p, 0.1f)).margin(1e-4));
}
