// BRDF table lookups. The batched kernel (the CPU renderer calls it once per
// block of vertices and light) works in two passes over blocks of 64 queries:
//   1. 8 queries at a time in vector lanes: the 4×4 taps of each square (its
//      corner sums, or a small square's texels) and its view weights (which
//      slices, how much of each);
//   2. one query at a time: per slice, the 4 rows × 2 pairs of neighbouring
//      entries (corner sums, or texels for a small square: shading::square_taps)
//      as 8 unaligned loads of 8 floats (lanes R G B R G B of entries a and
//      a+1, 2 unused), scaled by (view weight × row weight) and summed; the
//      column weights and the two entries of a pair are combined once at the end.
// The split keeps pass 2's dependency chains short (addresses are ready), so
// consecutive queries overlap. square_average is a batch of one.
#include <algorithm>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "src/brdf/brdf_table.h"
#include "src/shading/brdf_sat.h"

// The 32-byte vector helpers below are internal and inlined; without AVX
// (RSL_NATIVE off) GCC warns that returning one differs from an AVX build's
// ABI, which cannot matter here.
#if defined(__GNUC__)  // GCC and Clang
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace rsl {

// The scalar taps are the shading core's (src/shading/shading_core.h
// square_taps, shared with the GPU); pass 1 below computes the same lane by lane.
using shading::SquareTaps;
using shading::square_taps;

Color BrdfTable::slice_square_average(int s, const Vec2& center, float half_edge) const {
    const SquareTaps t = square_taps(center, half_edge, grid_.n);
    if (t.clipped_area <= 0.0f) return Color(0.0f);
    const size_t row = static_cast<size_t>(grid_.n + 1) * 3;
    const float* entries = lookup_.data() + static_cast<size_t>(s) * slice_floats_ + t.texels * (slice_floats_ / 2);
    Color sum(0.0f);
    for (int m = 0; m < 4; ++m)
        for (int l = 0; l < 4; ++l) {
            const float* c = entries + size_t(t.by[m]) * row + 3 * size_t(t.ax[l]);
            sum += t.wx[l] * t.wy[m] * Color(c[0], c[1], c[2]);
        }
    return (sum + offsets_[s] * t.offset_area) * t.inv_full_area;
}

namespace {

// Eight floats or ints (GCC/Clang vector extension): one AVX register with
// -march=native, two SSE registers otherwise.
typedef float Float8 __attribute__((vector_size(32)));
typedef int Int8 __attribute__((vector_size(32)));

inline Float8 load8(const float* p) {
    Float8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

// Weights of a pair's lanes: `first` on the first entry's R G B, `second`
// on the second's (and on the 2 unused lanes), as one blend.
inline Float8 pair_weights(float first, float second) {
    constexpr Int8 second_lanes{0, 0, 0, -1, -1, -1, -1, -1};
    return second_lanes ? (Float8{} + second) : (Float8{} + first);
}

inline void store8(float* p, const Float8& v) { std::memcpy(p, &v, sizeof v); }
inline void store8(int* p, const Int8& v) { std::memcpy(p, &v, sizeof v); }
inline Float8 splat(float x) { return Float8{} + x; }
inline Int8 splat(int x) { return Int8{} + x; }
inline Float8 to_float(const Int8& x) { return __builtin_convertvector(x, Float8); }
inline Int8 truncate(const Float8& x) { return __builtin_convertvector(x, Int8); }
inline Int8 min8(const Int8& a, const Int8& b) { return a < b ? a : b; }
inline Float8 min8(const Float8& a, const Float8& b) { return a < b ? a : b; }
inline bool any8(const Int8& mask) {
#if defined(__AVX__)
    return _mm256_movemask_ps((__m256)mask) != 0;
#else
    int any = 0;
    for (int i = 0; i < 8; ++i) any |= mask[i];
    return any != 0;
#endif
}
inline Float8 max8(const Float8& a, const Float8& b) { return a > b ? a : b; }
inline Float8 clamp8(const Float8& x, const Float8& hi) {  // clamp_to, lane by lane
    const Float8 y = max8(x, Float8{});
    return y < hi ? y : hi;
}
inline Float8 sqrt8(const Float8& x) {
#if defined(__AVX__)
    return (Float8)_mm256_sqrt_ps((__m256)x);
#else
    Float8 y;
    for (int i = 0; i < 8; ++i) y[i] = std::sqrt(x[i]);
    return y;
#endif
}

// 8 consecutive inputs from i; zeros past `count` (the last group of a batch).
// Always inlined: GCC would otherwise split off the tail copy as a function of
// its own, whose -Wpsabi warning (without AVX) the pragma above cannot reach.
[[gnu::always_inline]] inline Float8 load_group(const float* p, size_t i, size_t count) {
    if (i + 8 <= count) return load8(p + i);
    Float8 v{};
    for (size_t j = i; j < count; ++j) v[j - i] = p[j];
    return v;
}

// shading::corner_bracket, for 8 lanes.
inline void bracket8(const Float8& x, int n, Int8& lower, Float8& upper_weight) {
    lower = min8(truncate(x), splat(n - 1));
    upper_weight = x - to_float(lower);
}
// shading::texel_overlaps, for 8 lanes.
inline void overlaps8(const Int8& first, const Float8& lo, const Float8& hi, Float8 w[4]) {
    const Float8 left = to_float(first);  // + k: exact, as float(first + k)
    for (int k = 0; k < 4; ++k)
        w[k] = max8(min8(hi, left + float(k + 1)) - max8(lo, left + float(k)), Float8{});
}
// shading::sample_lerp, for 8 lanes: linear interpolation between V samples
// at (k + ½)/V of a coordinate in [0, 1] scaled by V (t = u·V − ½), clamped
// to the first and last sample.
inline void sample_lerp8(const Float8& x, int v, Int8& k0, Float8& w) {
    const Float8 t = clamp8(x, splat(static_cast<float>(v - 1)));
    k0 = min8(truncate(t), splat(v - 2));
    w = t - to_float(k0);
}

constexpr int kBlock = 64;  // queries per pass

// Pass 1's results for one block, per query: what pass 2 needs to read the
// table, with the view weights already multiplied into the row weights.
template <int Slices>
struct BlockTaps {
    alignas(32) int row_first[kBlock], row_second[kBlock];  // by[0]·(N+1)·3, by[2]·(N+1)·3
    alignas(32) int col_first[kBlock], col_second[kBlock];  // 3·ax[0], 3·ax[2]; + a layer for texels
    alignas(32) int first_slice[kBlock];
    alignas(32) float wx[4][kBlock];                         // the column weights
    alignas(32) float weight[Slices][4][kBlock];             // view weight × wy
    alignas(32) float offset_weight[Slices][kBlock];         // view weight × offset area
    alignas(32) float clipped[kBlock], inv_area[kBlock];
};

// Pass 1 for queries [begin, begin + count) of a block: what square_taps
// computes, 8 lanes at a time, on a table of N² texels and V view samples.
// Slices: 1 (view-independent), 2 (isotropic, linear in the view's plane
// radius), 4 (anisotropic, bilinear on the V×V grid).
template <int Slices>
inline void block_square_taps(const SquareQueries& q, size_t begin, size_t count, int n, int v, BlockTaps<Slices>& b) {
    const int row = (n + 1) * 3;
    const int layer = (n + 1) * row;  // the texels' layer follows the corner sums'
    const float scale = 0.5f * static_cast<float>(n);
    for (size_t g = 0; g < count; g += 8) {
        const size_t i = begin + g;
        Float8 h = q.half_edge ? load_group(q.half_edge, i, q.count) : splat(q.uniform_half_edge);
        h = max8(h, splat(shading::kMinSquareTexels / static_cast<float>(n)));  // as square_taps
        const Float8 cx = load_group(q.center_x, i, q.count), cy = load_group(q.center_y, i, q.count);
        const Float8 fn = splat(static_cast<float>(n));
        const Float8 x0 = clamp8((cx - h + 1.0f) * scale, fn), x1 = clamp8((cx + h + 1.0f) * scale, fn);
        const Float8 y0 = clamp8((cy - h + 1.0f) * scale, fn), y1 = clamp8((cy + h + 1.0f) * scale, fn);
        const Float8 clipped = (x1 - x0) * (y1 - y0);
        const Float8 edge = 2.0f * h * scale;
        // The corner sums' taps, and small squares' texels (lanes `small`).
        Int8 a0, a1, b0, b1;
        Float8 f0, f1, g0, g1;
        bracket8(x0, n, a0, f0);
        bracket8(x1, n, a1, f1);
        bracket8(y0, n, b0, g0);
        bracket8(y1, n, b1, g1);
        Float8 wx[4] = {1.0f - f1, f1, f0 - 1.0f, -f0};
        Float8 wy[4] = {1.0f - g1, g1, g0 - 1.0f, -g0};
        Int8 row_first = b1 * row, row_second = b0 * row, col_first = a1 * 3, col_second = a0 * 3;
        Float8 offset_area = clipped;
        const Int8 small = edge <= shading::kMaxTexelSquareTexels;
        if (any8(small)) {  // a batch of one environment light's queries has all its squares small, or none
            const Int8 ta = min8(truncate(x0), splat(n - 3)), tb = min8(truncate(y0), splat(n - 3));  // texel (ta, tb) first
            Float8 texel_wx[4], texel_wy[4];
            overlaps8(ta, x0, x1, texel_wx);
            overlaps8(tb, y0, y1, texel_wy);
            for (int m = 0; m < 4; ++m) wx[m] = small ? texel_wx[m] : wx[m], wy[m] = small ? texel_wy[m] : wy[m];
            row_first = small ? tb * row : row_first, row_second = small ? (tb + 2) * row : row_second;
            col_first = small ? ta * 3 + layer : col_first, col_second = small ? (ta + 2) * 3 + layer : col_second;
            offset_area = small ? Float8{} : offset_area;
        }
        Float8 view_weight[Slices];
        Int8 first = Int8{};
        if constexpr (Slices == 1) {
            view_weight[0] = splat(1.0f);
        } else if constexpr (Slices == 2) {
            const Float8 radius = sqrt8(clamp8(1.0f - load_group(q.view_z, i, q.count), splat(1.0f)));
            Float8 w;
            sample_lerp8(radius * float(v) - 0.5f, v, first, w);
            view_weight[0] = 1.0f - w, view_weight[1] = w;
        } else {
            // hemisphere_to_plane, clamped to the horizon, on the V×V grid.
            const Float8 z = max8(load_group(q.view_z, i, q.count), splat(-0.999f));
            const Float8 s = 1.0f / sqrt8(max8(1.0f + z, splat(1e-12f)));
            Float8 px = load_group(q.view_x, i, q.count) * s, py = load_group(q.view_y, i, q.count) * s;
            const Float8 len2 = px * px + py * py;
            const Float8 len = sqrt8(len2);
            px = len2 > 1.0f ? px / len : px;
            py = len2 > 1.0f ? py / len : py;
            Int8 i0, j0;
            Float8 wi, wj;
            sample_lerp8((px + 1.0f) * 0.5f * float(v) - 0.5f, v, i0, wi);
            sample_lerp8((py + 1.0f) * 0.5f * float(v) - 0.5f, v, j0, wj);
            first = j0 * v + i0;
            view_weight[0] = (1.0f - wi) * (1.0f - wj), view_weight[1] = wi * (1.0f - wj);
            view_weight[2] = (1.0f - wi) * wj, view_weight[3] = wi * wj;
        }
        store8(b.row_first + g, row_first);
        store8(b.row_second + g, row_second);
        store8(b.col_first + g, col_first);
        store8(b.col_second + g, col_second);
        store8(b.first_slice + g, first);
        for (int m = 0; m < 4; ++m) store8(b.wx[m] + g, wx[m]);
        for (int s = 0; s < Slices; ++s) {
            for (int m = 0; m < 4; ++m) store8(b.weight[s][m] + g, view_weight[s] * wy[m]);
            store8(b.offset_weight[s] + g, view_weight[s] * offset_area);
        }
        store8(b.clipped + g, clipped);
        store8(b.inv_area + g, 1.0f / (edge * edge));
    }
}

// Where pass 2 reads: the slices' entries (lookup_data(); the last slice
// padded so that an 8-float load past its end stays inside), and each
// slice's mean offset.
struct SliceEntries {
    int row = 0, view_samples = 0, last = 0;
    size_t slice_floats = 0;
    const float* entries = nullptr;
    const float* padded = nullptr;
    const Color* offsets = nullptr;
};

// Pass 2 for the block's `count` queries: per query and slice, the 4 rows ×
// 2 pairs as 8-float loads, weighted and summed, into out[begin + k].
template <int Slices>
inline void block_averages(const SliceEntries& t, const BlockTaps<Slices>& b, size_t begin, size_t count,
                           const ColorOutputs& out) {
    for (size_t k = 0; k < count; ++k) {
        float* const r = out.r + begin + k;
        float* const gr = out.g + begin + k;
        float* const bl = out.b + begin + k;
        if (b.clipped[k] <= 0.0f) {  // entirely outside the table (FMA would leave ±ulp residues)
            *r = *gr = *bl = 0.0f;
            continue;
        }
        const int rows[4] = {b.row_first[k], b.row_first[k] + t.row, b.row_second[k], b.row_second[k] + t.row};
        Float8 first[Slices], second[Slices];  // pairs (ax[0], ax[1]) and (ax[2], ax[3])
        Color offset(0.0f);
        for (int s = 0; s < Slices; ++s) {
            const int slice = b.first_slice[k] + (s & 1) + (s >> 1) * t.view_samples;
            const float* entries = slice == t.last ? t.padded : t.entries + slice * t.slice_floats;
            const float* first_pair = entries + b.col_first[k];
            const float* second_pair = entries + b.col_second[k];
            first[s] = Float8{}, second[s] = Float8{};
            for (int m = 0; m < 4; ++m) {
                const float w = b.weight[s][m][k];
                first[s] += w * load8(first_pair + rows[m]);
                second[s] += w * load8(second_pair + rows[m]);
            }
            offset += b.offset_weight[s][k] * t.offsets[slice];
        }
        for (int s = 1; s < Slices; ++s) first[0] += first[s], second[0] += second[s];
        const Float8 sum = first[0] * pair_weights(b.wx[0][k], b.wx[1][k]) +
                           second[0] * pair_weights(b.wx[2][k], b.wx[3][k]);
        // An average of ρ·cos ≥ 0; the corner sums' differences over a dark
        // region can cancel to a rounding below 0.
        *r = std::max((sum[0] + sum[3] + offset.r) * b.inv_area[k], 0.0f);
        *gr = std::max((sum[1] + sum[4] + offset.g) * b.inv_area[k], 0.0f);
        *bl = std::max((sum[2] + sum[5] + offset.b) * b.inv_area[k], 0.0f);
    }
}

}  // namespace

// The two passes (see the top of the file), block by block.
template <int Slices>
void BrdfTable::batch_kernel(const SquareQueries& q, const ColorOutputs& out) const {
    const SliceEntries entries{(grid_.n + 1) * 3, options_.view_samples, last_slice_, slice_floats_,
                               lookup_.data(), last_slice_padded_.data(), offsets_.data()};
    BlockTaps<Slices> b;
    for (size_t begin = 0; begin < q.count; begin += kBlock) {
        const size_t count = std::min(q.count - begin, static_cast<size_t>(kBlock));
        block_square_taps(q, begin, count, grid_.n, options_.view_samples, b);
        block_averages(entries, b, begin, count, out);
    }
}

void BrdfTable::square_average_batch(const SquareQueries& q, const ColorOutputs& out) const {
    if (view_independent_) {  // all slices equal: slice 0 at weight 1 is exact
        batch_kernel<1>(q, out);
    } else if (isotropic_) {
        batch_kernel<2>(q, out);
    } else {
        batch_kernel<4>(q, out);
    }
}

Color BrdfTable::square_average(const Vec2& center, float half_edge, const Vec3& view) const {
    Color out;
    SquareQueries q;
    q.center_x = &center.x, q.center_y = &center.y;
    q.half_edge = &half_edge;
    q.view_x = &view.x, q.view_y = &view.y, q.view_z = &view.z;
    q.count = 1;
    square_average_batch(q, ColorOutputs{&out.r, &out.g, &out.b});
    return out;
}

}  // namespace rsl
