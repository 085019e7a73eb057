// The shadow-mapped baseline (RenderOptions::shadow_maps, docs/design/GPU_DESIGN.md
// "Shadow-mapped visibility") against the exact visible fraction of a light's
// square under a half-plane occluder, computed analytically.
//
// Scene: a receiver plane (y = 0, |x|, |z| ≤ 1, 201² vertices) under an
// occluder rectangle at height H over x ∈ [−3, 0], |z| ≤ 2.5, which every
// receiver's rays meet as a half-plane (checked). One environment RSL
// (set_environment_lights) at several directions and sizes. Lambert, no
// fields: the colour without the maps is integral × BRDF average, so
// colour(maps) / colour(no maps) is the maps' lit fraction.
//
// Exact fraction: the square's 256² grid points in the vertex's equal-area
// plane above the horizon (exact_visibility.h's rule), direction by
// plane_to_hemisphere, the ray blocked where it meets the occluder. Every
// receiver vertex has the same frame, so a direction's crossing x0 + H·dx/dy
// is one sorted list of offsets, and a vertex's fraction a count in it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "src/core/error.h"
#include "src/gl/gl_renderer.h"
#include "src/render/cpu_renderer.h"
#include "tests/gl/gl_test_support.h"
#include "tests/render/render_test_scenes.h"
#include "tests/test_support.h"
#include "src/shading/frames.h"

namespace rsl {
namespace {

constexpr float kHeight = 0.4f;                      // the occluder's height
constexpr float kOccluderX0 = -3.0f, kOccluderX1 = 0.0f;  // its extent across the edge
constexpr float kOccluderHalfZ = 2.5f;               // and along it
constexpr int kReceiverCells = 200;                  // 201² vertices over [−1, 1]²
constexpr int kExactSamples = 256;                   // per side of the square

Scene half_plane_scene() {
    Scene scene = test::make_scene("shadow-maps");
    test::add_part(scene, test::make_plane(2.0f, kReceiverCells, "receiver"));
    Transform occluder;
    occluder.scale = Vec3(kOccluderX1 - kOccluderX0, 1.0f, 2.0f * kOccluderHalfZ);
    occluder.translation = Vec3(0.5f * (kOccluderX0 + kOccluderX1), kHeight, 0.0f);
    test::add_part(scene, test::make_plane(1.0f, 4, "occluder"), occluder);
    return scene;
}

// The exact visible fraction as a function of a receiver vertex's x: the
// sorted crossings x − x0 of the square's rays above the horizon.
struct ExactFraction {
    std::vector<float> crossings;  // H·dx/dy per ray, sorted
    size_t rays = 0;               // above the horizon
    float center_crossing = 0;     // of the square's centre: the hard shadow's edge
    float max_abs_z = 0;           // |H·dz/dy|: the rays stay inside the occluder's z extent

    ExactFraction(const SquareLight& light) {
        // The receiver's frame (make_plane: normal +y, tangent +x), as the renderers build it.
        const shading::LocalFrame frame = shading::frame_from_normal_tangent(Vec3(0, 1, 0), Vec3(1, 0, 0));
        const Vec2 center = shading::hemisphere_to_plane(shading::frame_to_local(frame, light.direction));
        auto to_world = [&](const Vec2& p) {
            const Vec3 local = shading::plane_to_hemisphere(p);
            return frame.x * local.x + frame.y * local.y + frame.z * local.z;
        };
        for (int j = 0; j < kExactSamples; ++j)
            for (int i = 0; i < kExactSamples; ++i) {
                const Vec2 p = center + light.half_edge * Vec2(2.0f * (float(i) + 0.5f) / kExactSamples - 1.0f,
                                                               2.0f * (float(j) + 0.5f) / kExactSamples - 1.0f);
                if (glm::dot(p, p) >= 1.0f) continue;
                ++rays;
                const Vec3 d = to_world(p);
                if (!(d.y > 1e-6f)) continue;  // parallel to the occluder: never meets it
                crossings.push_back(kHeight * d.x / d.y);
                max_abs_z = std::max(max_abs_z, std::abs(kHeight * d.z / d.y));
            }
        std::sort(crossings.begin(), crossings.end());
        const Vec3 c = to_world(center);
        center_crossing = kHeight * c.x / c.y;
    }
    // Rays of a vertex at x that cross y = H inside [kOccluderX0, kOccluderX1] are blocked.
    float operator()(float x) const {
        const auto lo = std::lower_bound(crossings.begin(), crossings.end(), kOccluderX0 - x);
        const auto hi = std::upper_bound(crossings.begin(), crossings.end(), kOccluderX1 - x);
        return rays == 0 ? 1.0f : 1.0f - float(hi - lo) / float(rays);
    }
    float hard(float x) const {  // one ray, the square's centre
        return x + center_crossing >= kOccluderX0 && x + center_crossing <= kOccluderX1 ? 0.0f : 1.0f;
    }
};

struct Errors {
    double penumbra_mean = 0;      // mean |maps − exact| over vertices with 0 < exact < 1
    double hard_penumbra_mean = 0; // the same for one hard tap at the square's centre
    size_t penumbra = 0;           // those vertices
    size_t far_wrong = 0;          // vertices farther than `margin` from the penumbra, not exactly 0 or 1 as exact
    size_t far = 0;
    float reach = 0;               // how far outside the penumbra a vertex is not exactly 0 or 1
    double mean_all = 0;           // mean |maps − exact| over every receiver vertex
};

// The maps' lit fraction per receiver vertex against the exact one.
Errors compare(const std::vector<Color>& shadowed, const std::vector<Color>& unshadowed, const TriangleMesh& receiver,
               const ExactFraction& exact, float texels) {
    Errors e;
    // x of the penumbra's ends (exact strictly between 0 and 1), over a fine scan.
    float lo = 1e9f, hi = -1e9f;
    for (int i = 0; i <= 20000; ++i) {
        const float x = -1.5f + 3.0f * float(i) / 20000.0f;
        const float f = exact(x);
        if (f > 0.0f && f < 1.0f) lo = std::min(lo, x), hi = std::max(hi, x);
    }
    // Away from it: beyond a few texels and a tenth of its width (PCSS's one
    // blocker distance for a tilted occluder widens or narrows the kernel).
    const float margin = texels + 0.1f * (hi - lo);
    double sum_all = 0;
    for (size_t v = 0; v < receiver.vertex_count(); ++v) {
        if (!(unshadowed[v].r > 0.0f)) FAIL("vertex " << v << " unlit without the maps");
        const float x = receiver.positions[v].x;
        const float maps = shadowed[v].r / unshadowed[v].r;
        const float truth = exact(x);
        sum_all += std::abs(maps - truth);
        if (truth > 0.0f && truth < 1.0f) {
            e.penumbra_mean += std::abs(maps - truth);
            e.hard_penumbra_mean += std::abs(exact.hard(x) - truth);
            ++e.penumbra;
        } else {
            if (maps != truth) e.reach = std::max(e.reach, std::max(lo - x, x - hi));
            if (x < lo - margin || x > hi + margin) {
                ++e.far;
                if (maps != truth) ++e.far_wrong;
            }
        }
    }
    e.penumbra_mean /= double(std::max<size_t>(e.penumbra, 1));
    e.hard_penumbra_mean /= double(std::max<size_t>(e.penumbra, 1));
    e.mean_all = sum_all / double(receiver.vertex_count());
    return e;
}

struct Case {
    Vec3 direction;        // towards the light's centre (normalized by single_rsl)
    float half_diagonal;   // the RSL's r: half-edge r / 2
};

const Case kCases[] = {
    {Vec3(0.0f, 1.0f, 0.0f), 0.1f},      // overhead, small
    {Vec3(0.5f, 0.866f, 0.0f), 0.3f},    // 30° towards +x: the edge moves to x = −H tan 30°
    {Vec3(-0.54f, 0.72f, 0.26f), 0.45f}, // ~37° towards −x and +z, large
    {Vec3(0.0f, 0.906f, 0.423f), 0.2f},  // 25° along the edge
};

// Mean |maps − exact| over the penumbra's vertices. Measured (llvmpipe; PCF
// at the right occluder distance, PCSS finding it): at 1024² 0.004–0.035
// (the large tilted light worst: one blocker distance for rays that meet the
// tilted occluder at different depths), at 256² 0.02–0.105 (the small
// overhead light worst: its penumbra is two texels wide). One hard tap at
// the square's centre (no filter) is off by 0.17–0.29, so it fails both.
double penumbra_bound(int resolution) { return resolution >= 1024 ? 0.045 : 0.125; }

const char* name(ShadowFilter filter) { return filter == ShadowFilter::Pcss ? "PCSS" : "PCF"; }

TEST_CASE("shadow-mapped visibility matches the exact fraction under a half-plane occluder", "[gl-shadow]") {
    test::gl_context();
    const Scene scene = half_plane_scene();
    const TriangleMesh& receiver = scene.parts[0].mesh;
    RenderOptions options;
    gl::GlRenderer gpu(scene, test::single_rsl(Vec3(0, 1, 0), 0.1f, Color(1.0f)), PartFields{}, options);
    VertexColors off = gpu.make_output(), on = gpu.make_output();

    for (const ShadowFilter filter : {ShadowFilter::Pcss, ShadowFilter::Pcf})
        for (const int resolution : {1024, 256})
            for (const Case& c : kCases) {
                gpu.set_environment_lights(test::single_rsl(c.direction, c.half_diagonal, Color(1.0f)));
                const SquareLight light = gpu.frame().environment_squares().at(0);
                const ExactFraction exact(light);
                REQUIRE(exact.max_abs_z + 1.0f < kOccluderHalfZ);  // a half-plane to every receiver ray

                options.shadow_maps.enabled = false;
                gpu.set_toggles(options);
                gpu.shade(off);
                options.shadow_maps = ShadowMapOptions{true, resolution, filter};
                gpu.set_toggles(options);
                gpu.shade(on);  // the maps' sphere is known from here on
                const float radius = gpu.shadow_map_sphere().w;
                REQUIRE(radius > 0.0f);
                // PCF assumes one occluder distance: here the right one, along
                // the light's centre to the plane y = H, × the sphere's radius.
                const float right_distance = kHeight / light.direction.y / radius;
                if (filter == ShadowFilter::Pcf) {
                    options.shadow_maps.pcf_distance = right_distance;
                    gpu.set_toggles(options);
                    gpu.shade(on);
                }
                // Outside the penumbra, beyond 2 texels and the bilinear
                // comparison's footprint, the maps are exactly 0 or 1 (no acne
                // on the lit receiver, nothing leaking into the umbra).
                const float texel = 2.0f * radius / float(resolution);
                const Errors e = compare(on.parts[0], off.parts[0], receiver, exact, 3.0f * texel);
                INFO(name(filter) << ' ' << resolution << "², light (" << light.direction.x << ", "
                                  << light.direction.y << ", " << light.direction.z << ") h " << light.half_edge
                                  << ": " << e.penumbra << " penumbra vertices, mean |maps − exact| "
                                  << e.penumbra_mean << " (one hard tap " << e.hard_penumbra_mean << "), over all "
                                  << e.mean_all << "; " << e.far << " vertices away from it, " << e.far_wrong
                                  << " not exactly 0 or 1; the farthest inexact vertex " << e.reach
                                  << " from it");
                CHECK(e.penumbra > 1000);
                CHECK(e.far > receiver.vertex_count() / 2);
                CHECK(e.far_wrong == 0);
                CHECK(e.penumbra_mean < penumbra_bound(resolution));
                CHECK(e.hard_penumbra_mean > penumbra_bound(resolution));  // an unfiltered map fails

                // PCF at three times the right distance: too wide a kernel fails the bound.
                if (filter == ShadowFilter::Pcf && resolution >= 1024 && c.half_diagonal >= 0.3f) {
                    options.shadow_maps.pcf_distance = 3.0f * right_distance;
                    gpu.set_toggles(options);
                    gpu.shade(on);
                    const Errors wide = compare(on.parts[0], off.parts[0], receiver, exact, 3.0f * texel);
                    INFO("PCF at 3x the distance: mean |maps − exact| " << wide.penumbra_mean);
                    CHECK(wide.penumbra_mean > penumbra_bound(resolution));
                }
            }

    // Off again: the colours of a renderer that never had maps, bit for bit.
    options.shadow_maps.enabled = false;
    gpu.set_toggles(options);
    gpu.shade(on);
    gl::GlRenderer fresh(scene, gpu.environment_lights(), PartFields{}, RenderOptions{});
    const VertexColors expected = fresh.shade();
    for (size_t p = 0; p < scene.parts.size(); ++p)
        for (size_t v = 0; v < expected.parts[p].size(); ++v)
            if (!(on.parts[p][v] == expected.parts[p][v]))
                FAIL("part " << p << " vertex " << v << " differs after the maps were switched off");
}

TEST_CASE("shadow maps: options out of range and the CPU renderer are refused", "[gl-shadow]") {
    test::gl_context();
    const Scene scene = half_plane_scene();
    RenderOptions options;
    options.shadow_maps.enabled = true;
    const RslSet lights = test::single_rsl(Vec3(0, 1, 0), 0.1f, Color(1.0f));
    CHECK_THROWS_WITH(CpuRenderer(scene, lights, PartFields{}, options), Catch::Contains("GL backend only"));
    for (const int resolution : {8, 16384}) {
        options.shadow_maps.resolution = resolution;
        CHECK_THROWS_WITH(gl::GlRenderer(scene, lights, PartFields{}, options), Catch::Contains("outside 16..8192"));
    }
    options.shadow_maps.resolution = 16;
    gl::GlRenderer gpu(scene, lights, PartFields{}, options);
    options.shadow_maps.pcf_distance = 0.0f;
    CHECK_THROWS_WITH(gpu.set_toggles(options), Catch::Contains("pcf_distance"));
    options.shadow_maps.pcf_distance = 0.1f;
    gpu.set_toggles(options);
    const VertexColors colors = gpu.shade();
    CHECK(colors.parts[0].size() == scene.parts[0].mesh.vertex_count());
    if (gpu.timings().clock) {  // this frame's times (timer queries report a frame late)
        CHECK(gpu.timings().shadow_ms > 0.0);
        CHECK(gpu.pass_times().find("shadow maps") != std::string::npos);
        gpu.shade_on_device();  // nothing moved: the maps are reused
        CHECK(gpu.timings().shadow_ms == 0.0);
    }
    // `rsl render`'s refusals: tests/render/render_cli_limits_test.cpp.
}

}  // namespace
}  // namespace rsl
