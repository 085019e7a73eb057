// The exact diffuse light's per-point gains (docs/design/RENDERER.md "Exact
// diffuse light"; the formulas are shading/diffuse_light.h's): one pass over
// the environment's squares per block, before its lights are looked up.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "src/render/block_scratch.h"
#include "src/render/cpu_renderer.h"
#include "src/shading/diffuse_light.h"

namespace rsl {

namespace {
// The constant part of the basis's D (kd = 1, f0 = 0): 1/π.
constexpr float kInvPbrPi = std::numbers::inv_pi_v<float>;
}  // namespace

// Each point's gain g = a·(E(n) / Σ_l I_l c_l − 1) over the environment's
// squares (shading/diffuse_light.h): brdf_queries adds g·c_l to light l's
// BRDF average, so the constant term a sees the exact irradiance E.
void CpuRenderer::diffuse_light_gains(BlockScratch& s, int part, int n) const {
    const Color a = part_constant_terms_[size_t(part)];
    s.gains = options_.exact_diffuse_light && options_.environment && (a != Color(0) || s.pbr) &&
              !environment_squares_.empty() && has_irradiance(environment_);
    if (!s.gains) return;
    const size_t lights = environment_squares_.size();
    if (s.cosines.size() < lights * kShadeBlock) s.cosines.resize(lights * kShadeBlock);  // warm-up only
    for (int k = 0; k < n; ++k) s.gain_r[k] = s.gain_g[k] = s.gain_b[k] = 0.0f;
    for (size_t l = 0; l < lights; ++l) {  // Σ_l I_l c_l, keeping each c_l for brdf_queries
        const SquareLight& sq = environment_squares_[l];
        const Vec3 d = sq.direction;
        const float h = sq.half_edge, spread = 0.6666667f * h * h;
        float* c = s.cosines.data() + l * kShadeBlock;
        // Each square against the unit disk, branch-free so that it
        // vectorizes: inside, the closed form; across the horizon, the
        // quadrature below; outside, 0.
        for (int k = 0; k < n; ++k) {
            const float x = d.x * s.xx[k] + d.y * s.xy[k] + d.z * s.xz[k];
            const float y = d.x * s.yx[k] + d.y * s.yy[k] + d.z * s.yz[k];
            const float z = d.x * s.zx[k] + d.y * s.zy[k] + d.z * s.zz[k];
            const float inv = 1.0f / std::sqrt(std::max(1.0f + z, 1e-12f));  // shading::hemisphere_to_plane
            const float px = x * inv, py = y * inv;
            s.tx[k] = px, s.ty[k] = py;
            const int where = shading::square_against_disk(Vec2(px, py), h);
            c[k] = where == 0 ? shading::cosine_floor(z - spread) : 0.0f;
            s.crossing[k] = int32_t(where == 1);
        }
        int across = 0;  // the squares across the horizon, compacted for a branch-free loop
        for (int k = 0; k < n; ++k) {
            s.index[across] = k;
            across += s.crossing[k];
        }
        for (int i = 0; i < across; ++i) s.qx[i] = s.tx[s.index[i]], s.qy[i] = s.ty[s.index[i]];
        for (int i = 0; i < across; ++i) s.qx[i] = shading::square_average_cosine_across(Vec2(s.qx[i], s.qy[i]), h);
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
        // A part varying per point: its point's constant term, w_D on D's (1/π).
        const Color ak = s.pbr ? Color(s.pbr_dr[k], s.pbr_dg[k], s.pbr_db[k]) * kInvPbrPi : a;
        s.gain_r[k] = shading::diffuse_light_gain(ak.r, e.r, s.gain_r[k]);
        s.gain_g[k] = shading::diffuse_light_gain(ak.g, e.g, s.gain_g[k]);
        s.gain_b[k] = shading::diffuse_light_gain(ak.b, e.b, s.gain_b[k]);
    }
}

}  // namespace rsl
