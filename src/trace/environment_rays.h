#pragma once
// env-rays: the Monte Carlo renderer a real-time engineer would run instead
// of fitted square lights (docs/BASELINES.md, "Many lights"). It estimates
// exactly the integral the ground truth sums (src/trace/ground_truth.h):
//
//   B(x, ω_o) = ∫ L(ω) ρ(ω, ω_o) cos θ V(x, ω) dω        (L: the piecewise-constant cube map)
//             + Σ_suns E_s ρ cos θ_s V                     (delta lights: one ray each, as the truth)
//             + Σ_lights ∫_cone L_e ρ cos θ V dω           (sphere lights)
//
// with N samples per point for the map and N per sphere light, so it
// converges to the truth as N grows. The map's integral combines two
// proposals with multiple importance sampling (balance heuristic): the map
// itself (EnvironmentSampler: texels ∝ luminance·Ω, points uniform inside)
// and the BRDF (BrdfSampler: ρ·cos tabulated on the equal-area grid); a
// share c_b of the N samples comes from the BRDF, the rest from the map, and
// each sample adds
//
//   L(ω) ρ(ω, ω_o) cos θ V(x, ω) / (N · (c_e pdf_env(ω) + c_b pdf_brdf(ω))),
//
// with ρ the exact model (never the table), so the estimate is unbiased
// whatever the tables' resolution. Sample i is a BRDF sample when
// (i + ξ)/N < c_b (ξ uniform per point): about c_b·N of them, each sample
// still a draw from its technique, so the sum stays unbiased (E[#BRDF] =
// c_b·N). Horizons, ray origins and occlusion are the truth's.
//
// Random numbers: counter-based hashes of (seed, stream, sample, dimension)
// (sample_sequence.h), streams per (part, vertex, lobe) or per pixel sample,
// so a frame is the same at any thread count. Each technique's samples are
// the points of a 2D Owen-scrambled Sobol sequence, warped by the
// distributions (their 2D CDF warps keep the stratification).
#include <atomic>
#include <memory>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/envmap.h"
#include "src/core/progress.h"
#include "src/core/scene.h"
#include "src/image/image_formation.h"
#include "src/formats/vertex_colors.h"
#include "src/rays/posed_scene.h"
#include "src/trace/brdf_sampler.h"
#include "src/trace/environment_sampler.h"
#include "src/trace/scene_integrand.h"

namespace rsl {

class ShadowBatch;

struct EnvironmentRaysOptions {
    static constexpr int kMaxSamples = 4096;
    int samples = 64;  // N: rays per point for the map, and N per sphere light (1 … kMaxSamples)
    uint64_t seed = 1;
    bool environment = true;  // the map and the suns
    bool local_lights = true;
    // c_b ∈ [0, 1]: the share of the map's samples drawn from the BRDF. 0.25:
    // on the robot, bunny and kitchen at N = 64, vertices' error 2.1 / 3.9 /
    // 5.5% against 2.7 / 4.9 / 6.6% at 0.5 and 3.7 / 2.8 / 5.2% at 0 (their
    // lobes are broad; the BRDF's share is insurance for sharp ones).
    float brdf_sampling_share = 0.25f;
    // Scrambled Sobol points (false: independent uniforms, to measure what stratification buys).
    bool stratified = true;
    BrdfSamplerOptions brdf_sampler;
};

class EnvironmentRays {
public:
    // `scene` must outlive this object. Builds one BVH per part, one BRDF
    // and its sampling tables per material lobe, the map's distribution;
    // poses everything at t. Throws rsl::Error on options out of range and
    // on what GroundTruth rejects.
    EnvironmentRays(const Scene& scene, const CubeMap& environment, float t, EnvironmentRaysOptions options = {});
    ~EnvironmentRays();

    // Moves parts, environment rotation, lights and camera to time t.
    void set_time(float t);
    float time() const { return posed_.time(); }
    const PosedScene& posed() const { return posed_; }
    const EnvironmentRaysOptions& options() const { return options_; }
    // As GroundTruth's: a textured part's diffuse lobe at unit texture, its specular lobe (else null).
    const Brdf& part_brdf(int part) const { return *lobes_.lobe[size_t(scene_.parts[size_t(part)].material)]; }
    const Brdf* part_specular_brdf(int part) const {
        return lobes_.specular[size_t(scene_.parts[size_t(part)].material)].get();
    }
    const EnvironmentSampler& environment_sampler() const { return environment_; }
    // The sampling tables of one of the scene's BRDF lobes (part_brdf, part_specular_brdf).
    const BrdfSampler& brdf_sampler(const Brdf& brdf) const;

    // Outgoing radiance at x towards wo_world (unit, world space); `brdf` one
    // of the scene's lobes, or a point's own (a material varying per point)
    // with `proposal`, the scene's lobe whose sampling tables draw its BRDF
    // samples (MIS stays unbiased: the weights use the tables' own density).
    // `stream` seeds the point's random numbers.
    Color shade(const SurfacePoint& x, const Vec3& wo_world, const Brdf& brdf, uint64_t stream,
                const Brdf* proposal = nullptr) const;
    // Every vertex of every part, towards the camera; all cores. Textured
    // parts are layered (VertexColors), as the truth's.
    VertexColors shade_vertices(const ProgressCallback& progress = {}) const;
    // A primary-ray hit, as GroundTruth::shade_hit; `pixel_stream` tells the
    // pixel sample's random numbers from every other's.
    Color shade_hit(const RayHit& hit, const Vec3& ray_direction, uint64_t pixel_stream) const;
    // shade_hit for trace_image (N rays per pixel sample): the stream is a
    // hash of the ray direction, which trace_image computes from the pixel
    // position alone, so the image is the same at any thread count.
    HitShader hit_shader() const;
    // Shadow rays traced so far by this object (all threads), for benchmarks.
    uint64_t rays_traced() const { return rays_traced_.load(std::memory_order_relaxed); }

    // The streams shade_vertices gives vertex `vertex` of `part`, and the
    // specular lobe's (a layered part's second integral).
    static uint64_t vertex_stream(int part, int vertex) { return (uint64_t(part) << 32) | uint32_t(vertex); }
    static uint64_t specular_stream(uint64_t stream) { return stream ^ (1ull << 63); }

private:
    void shade_environment(const SurfacePoint& x, const Vec3& wo, const Brdf& brdf, const BrdfSampler& sampler,
                           uint64_t stream, ShadowBatch& batch) const;
    void shade_suns(const SurfacePoint& x, const Vec3& wo, const Brdf& brdf, ShadowBatch& batch) const;
    void shade_light(const SurfacePoint& x, const Vec3& origin, const Vec3& wo, const Brdf& brdf, size_t light,
                     const Color& radiance, uint64_t stream, ShadowBatch& batch) const;
    class Points;

    const Scene& scene_;
    EnvironmentRaysOptions options_;
    PosedScene posed_;
    SceneLobes lobes_;
    std::vector<const Brdf*> sampled_brdfs_;                          // the lobes that have tables ...
    std::vector<std::unique_ptr<BrdfSampler>> brdf_samplers_;         // ... and their tables
    EnvironmentSampler environment_;
    Mat3 rotation_{1.0f}, inverse_rotation_{1.0f};  // the map's frame → world at t, and back
    std::vector<Vec3> sun_directions_;
    PosedLights lights_;
    Vec3 camera_{0};
    mutable std::atomic<uint64_t> rays_traced_{0};
};

}  // namespace rsl
