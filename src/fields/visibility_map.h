#pragma once
// Per-vertex self-visibility maps on the equal-area hemisphere grid, traced
// with Embree, and turned into VDTs (the raw SVDF before compression).
//
// Sampling, adaptive at two levels (most of a visibility map is far from its
// boundary, where rays tell nothing new):
//  1. one ray through the center of every texel with even (i, j) inside the
//     unit disk; the other texels get a ray only where the even texels around
//     them disagree (features thinner than two texels between them can be
//     missed: measured by `rsl bench fields`, "svdf sampling");
//  2. k×k stratified rays in the texels where the map changes (a texel whose
//     4-neighbour differs): the boundary gets sub-texel coverage for a
//     fraction of the cost of supersampling everything.
//
// Below the horizon (texels whose center lies outside the unit disk) no ray is
// traced; their value follows BelowHorizon. Extend (the default) copies the
// nearest traced texel along the radial direction: the BRDF factor is zero
// below the horizon, so the visibility average that matters for a square
// straddling the horizon is the one over its above-horizon part, which the
// extension reproduces best (measured by `rsl bench fields`, docs/design/FIELDS.md).
#include <cstdint>
#include <vector>

#include "src/fields/visibility_distance_table.h"
#include "src/core/math.h"
#include "src/core/mesh.h"
#include "src/core/progress.h"
#include "src/rays/ray_scene.h"

namespace rsl {

enum class BelowHorizon : uint8_t { Blocked = 0, Visible = 1, Extend = 2 };

struct VisibilityMapOptions {
    int resolution = 32;
    int supersampling = 2;  // k: k×k rays in texels on the boundary; 1 = one ray per texel
    bool coarse_to_fine = true;  // false: one ray in every texel (reference)
    BelowHorizon below_horizon = BelowHorizon::Extend;
    VdtMode mode = VdtMode::CoverageAware;
};

// Local directions of the grid, computed once per resolution.
class HemisphereSampling {
public:
    // Texels whose center lies within plane radius max_radius are traced (1:
    // the upper hemisphere, SVDF; up to √2 covers the whole square, OVDF).
    HemisphereSampling(int resolution, int supersampling, bool coarse_to_fine = true, float max_radius = 1.0f);

    int resolution() const { return n_; }
    int supersampling() const { return k_; }
    // Texels whose center is above the horizon, and their center directions (local).
    const std::vector<int>& traced_texels() const { return traced_; }
    const std::vector<Vec3>& center_directions() const { return center_dirs_; }
    // k×k subsample directions of texel t (those inside the disk; may be fewer).
    int subsample_begin(int texel) const { return sub_begin_[texel]; }
    int subsample_end(int texel) const { return sub_begin_[texel + 1]; }
    const std::vector<Vec3>& subsample_directions() const { return sub_dirs_; }
    // For a texel not traced: the traced texel it copies under Extend (−1 if none).
    int extension_source(int texel) const { return extension_source_[texel]; }
    bool is_traced(int texel) const { return traced_mask_[texel] != 0; }
    // Positions in traced_texels() of the texels with even (i, j) (traced
    // first) and of the others (traced only where the even ones disagree).
    const std::vector<int>& coarse_positions() const { return coarse_; }
    const std::vector<int>& fine_positions() const { return fine_; }

private:
    int n_, k_;
    std::vector<int> traced_;
    std::vector<uint8_t> traced_mask_;
    std::vector<Vec3> center_dirs_;
    std::vector<int> sub_begin_;
    std::vector<Vec3> sub_dirs_;
    std::vector<int> extension_source_;
    std::vector<int> coarse_, fine_;
};

// Scratch buffers for one thread.
struct VisibilityScratch {
    std::vector<Vec3> world_dirs;
    std::vector<uint8_t> hits;
    std::vector<float> coverage;
    std::vector<int> boundary, fine;
    VdtWorkspace vdt;
};

// Coverage map (n×n, visible fractions) seen from `origin` in `frame`.
void trace_coverage(const RayScene& scene, const HemisphereSampling& sampling, const Vec3& origin,
                    const Frame& frame, BelowHorizon below_horizon, VisibilityScratch& scratch,
                    float* coverage);

// The frame a vertex's tables live in (docs/design/METHOD.md: z = normal, x = tangent).
inline Frame vertex_frame(const TriangleMesh& mesh, size_t v) {
    const Vec3 t = v < mesh.tangents.size() ? Vec3(mesh.tangents[v]) : Vec3(0);
    return Frame::from_normal_tangent(mesh.normals[v], t);
}

// VDTs of every vertex of `mesh` (vertices × n², plane units) against `scene`
// (which holds the mesh, placed by the identity). Multi-threaded (TBB).
// With `vertices`, only those (in that order).
std::vector<float> trace_vertex_vdts(const RayScene& scene, const TriangleMesh& mesh,
                                     const VisibilityMapOptions& options, const ProgressCallback& progress = {},
                                     const std::vector<uint32_t>* vertices = nullptr);

}  // namespace rsl
