// The exact diffuse light's per-point gains (docs/design/RENDERER.md "Exact
// diffuse light"; the formulas are shading/diffuse_light.h's): one pass over
// the environment's squares per block, before its lights are looked up.
#include "src/render/block_scratch.h"
#include "src/render/cpu_renderer.h"
#include "src/shading/diffuse_light.h"

namespace rsl {

// Each point's gain g = a·(E(n) / Σ_l I_l c_l − 1) over the environment's
// squares (shading/diffuse_light.h): brdf_queries adds g·c_l to light l's
// BRDF average, so the constant term a sees the exact irradiance E.
void CpuRenderer::diffuse_light_gains(BlockScratch& s, int part, int n) const {
    const Color a = part_constant_terms_[size_t(part)];
    s.gains = options_.exact_diffuse_light && options_.environment && a != Color(0) &&
              !environment_squares_.empty() && has_irradiance(environment_);
    if (!s.gains) return;
    const size_t lights = environment_squares_.size();
    if (s.cosines.size() < lights * kShadeBlock) s.cosines.resize(lights * kShadeBlock);  // warm-up only
    for (int k = 0; k < n; ++k) s.gain_r[k] = s.gain_g[k] = s.gain_b[k] = 0.0f;
    for (size_t l = 0; l < lights; ++l) {  // Σ_l I_l c_l, keeping each c_l for brdf_queries
        const SquareLight& sq = environment_squares_[l];
        const float h = sq.half_edge, rim = 1.0f - kSqrt2 * h, reach = 1.0f + kSqrt2 * h;
        const float lowest = 1.0f - reach * reach, spread = 0.6666667f * h * h;
        float* c = s.cosines.data() + l * kShadeBlock;
        // Inside the hemisphere's disk (|p|² = 1 − z): the closed form,
        // branch-free; a square across the horizon: the quadrature below.
        for (int k = 0; k < n; ++k) {
            const float z = sq.direction.x * s.zx[k] + sq.direction.y * s.zy[k] + sq.direction.z * s.zz[k];
            c[k] = shading::cosine_floor(z - spread);
            s.crossing[k] = int32_t(z > lowest) & int32_t(1.0f - z > rim * rim || rim < 0.0f);
        }
        int across = 0;  // the squares across the horizon, compacted for a branch-free loop
        for (int k = 0; k < n; ++k) {
            if (!s.crossing[k]) continue;
            const Vec3 local(sq.direction.x * s.xx[k] + sq.direction.y * s.xy[k] + sq.direction.z * s.xz[k],
                             sq.direction.x * s.yx[k] + sq.direction.y * s.yy[k] + sq.direction.z * s.yz[k],
                             sq.direction.x * s.zx[k] + sq.direction.y * s.zy[k] + sq.direction.z * s.zz[k]);
            const Vec2 p = hemisphere_to_plane(local);
            s.tx[across] = p.x, s.ty[across] = p.y, s.index[across] = k;
            ++across;
        }
        for (int i = 0; i < across; ++i)
            s.qx[i] = shading::square_average_cosine_across(Vec2(s.tx[i], s.ty[i]), h);
        for (int i = 0; i < across; ++i) c[s.index[i]] = s.qx[i];
        for (int k = 0; k < n; ++k)
            s.gain_r[k] += sq.integral.r * c[k], s.gain_g[k] += sq.integral.g * c[k], s.gain_b[k] += sq.integral.b * c[k];
    }
    for (int k = 0; k < n; ++k) {
        // A view below the horizon has ρ = 0 (brdf_queries): no gain either.
        if (!(s.vz[k] > 0.0f)) {
            s.gain_r[k] = s.gain_g[k] = s.gain_b[k] = 0.0f;
            continue;
        }
        const Color e = environment_irradiance(environment_, frame_, Vec3(s.zx[k], s.zy[k], s.zz[k]));
        s.gain_r[k] = shading::diffuse_light_gain(a.r, e.r, s.gain_r[k]);
        s.gain_g[k] = shading::diffuse_light_gain(a.g, e.g, s.gain_g[k]);
        s.gain_b[k] = shading::diffuse_light_gain(a.b, e.b, s.gain_b[k]);
    }
}

}  // namespace rsl
