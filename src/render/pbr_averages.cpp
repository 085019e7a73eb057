// Parts whose roughness and metallic vary per point (docs/design/BRDF.md
// "Textured roughness and metallic"): the block's points' weights on the
// scene's basis tables, and their BRDF averages in place of a part table's.
#include <algorithm>

#include "src/core/error.h"
#include "src/render/block_scratch.h"
#include "src/render/cpu_renderer.h"
#include "src/shading/pbr_basis.h"

namespace rsl {

void CpuRenderer::set_pbr_point(BlockScratch& s, int k, const Color& base, const PbrPoint& point) const {
    const shading::PbrWeights w = shading::pbr_weights(base, point.metallic, point.roughness);
    s.pbr_dr[k] = w.diffuse.r, s.pbr_dg[k] = w.diffuse.g, s.pbr_db[k] = w.diffuse.b;
    s.pbr_er[k] = w.dielectric.r, s.pbr_eg[k] = w.dielectric.g, s.pbr_eb[k] = w.dielectric.b;
    s.pbr_mr[k] = w.metal.r, s.pbr_mg[k] = w.metal.g, s.pbr_mb[k] = w.metal.b;
    s.pbr_level[k] = w.level;
    s.pbr_upper[k] = w.upper;
    s.pbr_first = std::min(s.pbr_first, w.upper < 1.0f ? w.level : w.level + 1);
    s.pbr_last = std::max(s.pbr_last, w.upper > 0.0f ? w.level + 1 : w.level);
    s.pbr_metal = s.pbr_metal || w.metal != Color(0);
}

void CpuRenderer::load_block_pbr(BlockScratch& s, int part, int n) const {
    const std::vector<PbrPoint>& points = part_pbr_points_[size_t(part)];
    s.pbr = !points.empty();
    if (!s.pbr) return;
    s.pbr_first = kPbrLevels, s.pbr_last = -1, s.pbr_metal = false;
    for (int k = 0; k < n; ++k) set_pbr_point(s, k, part_pbr_base_[size_t(part)], points[size_t(s.vertex[k])]);
}

// ρ = w_D·D + Σ_j level weight × (w_e·S(0.04, r_j) + w_m·S(1, r_j)) per
// query (shading/pbr_basis.h); D into the diffuse sums, S into the
// specular ones when the part is layered (textured base colour).
void CpuRenderer::pbr_averages(BlockScratch& s, const SquareQueries& queries, int m, bool layered) const {
    const PbrBasisTables& basis = library_.pbr_basis();
    RSL_CHECK(basis.diffuse);
    basis.diffuse->square_average_batch(queries, ColorOutputs{s.br, s.bg, s.bb});
    for (int i = 0; i < m; ++i) {
        const int k = s.index[i];
        s.br[i] *= s.pbr_dr[k], s.bg[i] *= s.pbr_dg[k], s.bb[i] *= s.pbr_db[k];
    }
    float* out_r = layered ? s.spr : s.br;
    float* out_g = layered ? s.spg : s.bg;
    float* out_b = layered ? s.spb : s.bb;
    if (layered)
        for (int i = 0; i < m; ++i) s.spr[i] = s.spg[i] = s.spb[i] = 0.0f;
    for (int j = s.pbr_first; j <= s.pbr_last; ++j)
        for (int metal = 0; metal < (s.pbr_metal ? 2 : 1); ++metal) {
            const BrdfTable* table = (metal ? basis.metal : basis.dielectric)[size_t(j)].get();
            RSL_CHECK(table);  // MaterialLibrary builds every level the material's texture reaches
            table->square_average_batch(queries, ColorOutputs{s.tr, s.tg, s.tb});
            const float* wr = metal ? s.pbr_mr : s.pbr_er;
            const float* wg = metal ? s.pbr_mg : s.pbr_eg;
            const float* wb = metal ? s.pbr_mb : s.pbr_eb;
            for (int i = 0; i < m; ++i) {
                const int k = s.index[i];
                const float w = shading::pbr_level_weight(s.pbr_level[k], s.pbr_upper[k], j);
                out_r[i] += w * wr[k] * s.tr[i], out_g[i] += w * wg[k] * s.tg[i], out_b[i] += w * wb[k] * s.tb[i];
            }
        }
}

}  // namespace rsl
