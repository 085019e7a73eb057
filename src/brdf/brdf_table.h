#pragma once
// BRDF summed-area tables (RSL paper §4.2; frames and measure of docs/design/METHOD.md).
//
// A table holds, for each tabulated view direction (a "slice"), the texel
// averages of ρ·cosθ_i on the equal-area N×N grid of light directions
// (TexelSampler) and their summed-area table. Layout (docs/design/BRDF.md):
//   isotropic models: V slices in the VIEW-ALIGNED frame (the view has azimuth
//     0, i.e. lies in the +y half of the y-z plane; see to_view_aligned), at
//     view plane radii |p(ω_o)| = (k + ½)/V, k = 0..V−1 (a 3D table);
//   anisotropic models: V×V slices in the TANGENT frame, one per texel center
//     of a V×V grid of view directions (a 4D table); grid points outside the
//     disk use the direction at radius (V − ½)/V with the same azimuth, so the
//     bilinear view interpolation is defined up to the horizon.
//
// SAT entry (a, b), 0 ≤ a, b ≤ N, is the sum of the texels (i, j) with i < a,
// j < b: it sits on texel CORNERS. Bilinear interpolation between corners is
// then the exact integral of the piecewise-constant table, so a square average
// is exact for the table, continuous in center and size, and exact to float
// precision for texel-aligned squares. Sums are accumulated in double and
// stored in float, by default minus the slice's mean texel value times the
// corner's area (Hensley et al. 2005), which keeps stored values small.
#include <cstddef>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/hemisphere.h"

namespace rsl {

enum class SatStorage {
    Float,            // S(a, b) in float
    FloatMeanOffset,  // S(a, b) − μ·a·b in float, μ the slice's mean texel (per channel)
};

struct BrdfTableOptions {
    // N: light directions on the N×N equal-area grid, and V: isotropic
    // views. A glossy lobe under a sun is only a few texels wide at N = 64, and
    // it moves between two views by twice their spacing, so both were the
    // largest part of the glossy robot's unshadowed error under the sun
    // (docs/design/BRDF.md, "Table resolution").
    int resolution = 96;
    int view_samples = 64;             // V: isotropic V polar samples
    int anisotropic_view_samples = 32; // anisotropic tables: min(V, this)² directions (each slice is N² texels)
    int interior_supersampling = 2;  // sub-samples per texel side inside the disk
    int edge_supersampling = 4;      // ... on texels the horizon crosses
    SatStorage storage = SatStorage::FloatMeanOffset;
};

// A batch of square lookups for one light and many vertices (structure of
// arrays). Centers and views are in the table's frame; for isotropic tables
// only view_z (cos θ_o) is read and view_x/view_y may be null.
struct SquareQueries {
    const float* center_x = nullptr;
    const float* center_y = nullptr;
    const float* half_edge = nullptr;  // per query, or null: uniform_half_edge for all
    float uniform_half_edge = 0.0f;
    const float* view_x = nullptr;
    const float* view_y = nullptr;
    const float* view_z = nullptr;
    size_t count = 0;
};
struct ColorOutputs {
    float* r = nullptr;
    float* g = nullptr;
    float* b = nullptr;
};

class BrdfTable {
public:
    // Tabulates `brdf` (multi-threaded over slices). The table does not keep the BRDF.
    static std::shared_ptr<const BrdfTable> build(const Brdf& brdf, const BrdfTableOptions& options = {});
    // The views tabulated for V view samples: isotropic, V polar views at
    // plane radius (k + ½)/V; anisotropic, the V×V grid's texel centres, those
    // beyond radius (V − ½)/V pulled in to it.
    static std::vector<Vec3> slice_views(bool isotropic, int view_samples);

    bool isotropic() const { return isotropic_; }
    // Every slice holds the same texels (e.g. Lambert, or Phong with ks = 0),
    // detected at build: lookups then read one slice whatever the view.
    bool view_independent() const { return view_independent_; }
    const BrdfTableOptions& options() const { return options_; }
    const PlaneGrid& grid() const { return grid_; }
    int slice_count() const { return static_cast<int>(slice_views_.size()); }
    // The view direction slice s was tabulated for (table frame).
    const Vec3& slice_view(int s) const { return slice_views_[s]; }
    // The tabulated texel average of ρ·cos, texel (i, j) of slice s.
    Color texel(int s, int i, int j) const {
        const size_t layer = slice_floats_ / 2, entry_index = size_t(j) * (grid_.n + 1) + size_t(i);
        const float* entry = lookup_.data() + s * slice_floats_ + layer + 3 * entry_index;
        return Color(entry[0], entry[1], entry[2]);
    }

    // Average of ρ·cos over the axis-aligned square of center `center` and
    // half-edge `half_edge` (plane units, table frame) for view direction `view`
    // (table frame; iso tables read only view.z). The parts of the square
    // outside [−1, 1]² count as 0; the average is over the full square area.
    // Views are interpolated linearly (iso) / bilinearly (aniso) between slices;
    // views below the horizon are clamped to it.
    Color square_average(const Vec2& center, float half_edge, const Vec3& view) const;
    // The same for one slice, without view interpolation.
    Color slice_square_average(int s, const Vec2& center, float half_edge) const;
    // Batched square_average: out[k] for queries k = 0..count−1. No allocation;
    // split large batches across threads at the call site. square_average is
    // a batch of one, so the two agree bit for bit (brdf_table_lookup.cpp).
    void square_average_batch(const SquareQueries& queries, const ColorOutputs& out) const;

    // Raw storage (for the GL uploader), what shading::square_taps reads:
    // per slice s two layers of (N+1)² RGB entries, entry (a, b) of layer l
    // at (((2s + l)·(N+1) + b)·(N+1) + a)·3. Layer 0: the corner sums (add
    // offset(s)·a·b per channel to get S(a, b); offsets are 0 with
    // SatStorage::Float); layer 1: the texels (row N and column N zero).
    const std::vector<float>& lookup_data() const { return lookup_; }
    const Color& offset(int s) const { return offsets_[s]; }
    size_t memory_bytes() const;

private:
    BrdfTable() = default;
    void store_slice(int s, const Color* texels);
    void detect_view_independence();
    template <int Slices>
    void batch_kernel(const SquareQueries& queries, const ColorOutputs& out) const;

    bool isotropic_ = true;
    bool view_independent_ = false;
    size_t slice_floats_ = 0;  // 2 layers × (N+1)² × 3
    int last_slice_ = 0;
    BrdfTableOptions options_;
    PlaneGrid grid_;
    std::vector<Vec3> slice_views_;
    std::vector<float> lookup_;  // lookup_data()
    // The batch kernel reads a pair of entries as 8 floats, 2 past the pair:
    // past the end of lookup_ on the last slice's last row. It reads that slice here.
    std::vector<float> last_slice_padded_;  // the last slice + 8 zeros
    std::vector<Color> offsets_;
};

// The view-aligned frame of isotropic tables: rotates local direction w about
// the normal so that the view `wo` gets azimuth 0 (φ from +y towards +x, as in
// hemisphere.h). A view along the normal leaves w unchanged.
inline Vec3 to_view_aligned(const Vec3& w, const Vec3& wo) {
    const float len2 = wo.x * wo.x + wo.y * wo.y;
    if (len2 < 1e-16f) return w;
    const float s = 1.0f / std::sqrt(len2);
    const float sx = wo.x * s, cy = wo.y * s;  // sin φ_o, cos φ_o
    // New axes: y' = (sin φ, cos φ, 0), x' = y' × z = (cos φ, −sin φ, 0).
    return Vec3(w.x * cy - w.y * sx, w.x * sx + w.y * cy, w.z);
}

}  // namespace rsl
