#pragma once
// The reference every error figure is measured against: direct lighting from
// the whole environment map and every local light, with a shadow ray per
// sample against all parts in their current poses (docs/design/TRUTH.md).
//
//   B(x, ω_o) = Σ_k L_k ρ(ω_k, ω_o) cos θ_k V(x, ω_k) Ω_k        (every cube-map texel k)
//             + Σ_suns E_s ρ(ω_s, ω_o) cos θ_s V(x, ω_s)           (glTF suns: irradiance E_s)
//             + Σ_lights ∫_cone L_e ρ cos θ V dω                  (sphere lights)
//
// Cube-map texels carry their exact solid angles Ω_k; the environment's
// rotation at t turns the texel directions (the map is not resampled). A sphere
// light of radius a and power Φ is a uniform Lambertian emitter of radiance
// L_e = Φ / (4π² a²), integrated over the cone it subtends with stratified
// uniform-cone samples refined until two successive grids agree.
#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/envmap.h"
#include "src/core/scene.h"
#include "src/core/sphere_light.h"
#include "src/rays/posed_scene.h"
#include "src/core/progress.h"
#include "src/formats/vertex_colors.h"
#include "src/trace/scene_integrand.h"

namespace rsl {

struct GroundTruthOptions {
    // Sub-texel grid: at least S×S rays per texel, each with its own exact
    // solid angle (midpoint rule on a finer grid of the same piecewise-constant map).
    int texel_subdivision = 1;
    // Bright texels are cut finer, until no sample carries more than this
    // share of the map's luminance (at most kMaxAdaptiveSubdivision² samples
    // a texel): a sun's one texel would otherwise cast a hard shadow from its
    // centre where the map's integral has a penumbra (docs/design/TRUTH.md).
    // 0: every texel gets texel_subdivision² samples.
    float max_sample_share = kDefaultMaxSampleShare;
    static constexpr float kDefaultMaxSampleShare = 4e-4f;
    static constexpr int kMaxAdaptiveSubdivision = 32;
    bool environment = true;
    bool local_lights = true;
    // false: every sample above the shading horizon counts as visible (no
    // shadow ray, no geometric-side test): the unshadowed integral.
    bool shadows = true;
    // Sphere lights: grids of side 8, 16, 32, … up to light_max_side; stop
    // when the luminance of two successive estimates differs by less than
    // light_tolerance (relative).
    float light_tolerance = 1e-3f;
    int light_max_side = 64;
};

// The environment as the ground truth integrates it: one entry per (sub-)texel
// with nonzero radiance, structure of arrays, directions already rotated.
struct EnvironmentSamples {
    std::vector<Vec3> directions;         // world space, unit
    std::vector<Color> radiance_weights;  // L_k · Ω_k
    size_t size() const { return directions.size(); }
    // Each texel cut into S×S cells, S = max(subdivision, the least S that
    // brings the texel's share of the map's luminance per cell to
    // max_sample_share or below, at most kMaxAdaptiveSubdivision); 0: no adaptive cut.
    static EnvironmentSamples from_cube(const CubeMap& map, const Mat3& rotation, int subdivision,
                                        float max_sample_share = 0.0f);
};

// The truth's memory (src/core/memory_limit.h): the meshes, the posed copy
// and its BVH, the colours and a width × height image (0 × 0: none). Throws
// rsl::Error naming the scene's file when it passes the limit; GroundTruth
// checks it without the image, `rsl truth` with its image before any work.
void check_truth_memory(const Scene& scene, int image_width = 0, int image_height = 0);

class GroundTruth {
public:
    // `scene` must outlive this object. Builds one BVH per part and one BRDF
    // per material; poses everything at t.
    GroundTruth(const Scene& scene, const CubeMap& environment, float t, GroundTruthOptions options = {});

    // Moves parts, environment, lights and camera to time t (no BVH rebuild).
    void set_time(float t);
    float time() const { return posed_.time(); }
    const PosedScene& posed() const { return posed_; }
    // A textured part's material is two lobes (make_brdf_lobes): part_brdf is
    // its diffuse lobe at unit texture, part_specular_brdf (null otherwise)
    // the specular one; each is integrated on its own (twice the rays).
    const Brdf& part_brdf(int part) const { return *lobes_.lobe[size_t(scene_.parts[size_t(part)].material)]; }
    const Brdf* part_specular_brdf(int part) const {
        return lobes_.specular[size_t(scene_.parts[size_t(part)].material)].get();
    }
    // The whole material at unit texture (part_brdf + part_specular_brdf; the
    // same as part_brdf when untextured): what colours at unit texture integrate.
    const Brdf& part_unit_texture_brdf(int part) const {
        return *lobes_.whole[size_t(scene_.parts[size_t(part)].material)];
    }
    const Texture* part_texture(int part) const {
        return scene_.materials[scene_.parts[part].material].base_color_texture.get();
    }
    Vec3 camera_position() const { return camera_; }
    size_t environment_sample_count() const { return environment_.size(); }

    // Outgoing radiance at x towards wo_world (unit, world space).
    Color shade(const SurfacePoint& x, const Vec3& wo_world, const Brdf& brdf) const;
    // Every vertex of every part, towards the camera; all cores. Textured
    // parts are layered (VertexColors): diffuse at unit texture, specular.
    VertexColors shade_vertices(const ProgressCallback& progress = {}) const;
    // The truth at a primary-ray hit, per pixel: a textured part's diffuse
    // lobe times its texture at the hit's texture coordinates, plus specular.
    Color shade_hit(const RayHit& hit, const Vec3& ray_direction) const;
    // Shadow rays traced so far by this object (all threads), for benchmarks.
    uint64_t rays_traced() const { return rays_traced_.load(std::memory_order_relaxed); }

private:
    Color shade_environment(const SurfacePoint& x, const Vec3& origin, const Vec3& wo, const Brdf& brdf,
                            uint64_t& rays) const;
    Color shade_light(const SurfacePoint& x, const Vec3& origin, const Vec3& wo, const Brdf& brdf,
                      const Vec3& center, float radius, const Color& radiance, uint64_t& rays) const;

    const Scene& scene_;
    CubeMap cube_;  // a copy: small (6N² colours) and it frees callers from lifetimes
    GroundTruthOptions options_;
    PosedScene posed_;
    SceneLobes lobes_;
    EnvironmentSamples environment_;
    PosedLights lights_;
    Vec3 camera_{0};
    mutable std::atomic<uint64_t> rays_traced_{0};
};

}  // namespace rsl
