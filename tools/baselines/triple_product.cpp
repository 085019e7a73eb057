// The tripling-coefficient evaluation of Σ_k L_k (VΩ)_k ρ̃_k (triple_product.h).
#include "tools/baselines/triple_product.h"

#include <algorithm>
#include <bit>

#include "src/core/error.h"
#include "tools/baselines/haar.h"

namespace rsl::triple {

namespace {

// The mean over the detail's square of the function whose dense Haar
// coefficients (one face) are `face`: φ's value 1/N plus, for every strictly
// coarser square containing it, that square's details times their value
// (±1/side) on the quadrant the square lies in.
template <class T>
T ancestor_mean(const T* face, int n, const Detail& d) {
    T sum = face[0] * (1.0f / float(n));
    int half = d.half, x = d.x, y = d.y;
    while (half > 1) {
        const float sx = (x & 1) ? -1.0f : 1.0f, sy = (y & 1) ? -1.0f : 1.0f;
        half >>= 1, x >>= 1, y >>= 1;
        const float value = float(half) / float(n);  // 1 / the parent's side n/half
        sum += (face[y * n + x + half] * sx + face[(y + half) * n + x] * sy + face[(y + half) * n + x + half] * (sx * sy)) *
               value;
    }
    return sum;
}

bool nonzero(const Color& c) { return c.r != 0.0f || c.g != 0.0f || c.b != 0.0f; }

}  // namespace

Detail decode(int index, int n) {
    Detail d;
    const int per_face = n * n;
    d.face_base = index / per_face * per_face;
    const int rest = index - d.face_base, i = rest % n, j = rest / n;
    if (i == 0 && j == 0) return d;  // the scaling coefficient
    d.half = int(std::bit_floor(unsigned(std::max(i, j))));
    d.type_x = i >= d.half, d.type_y = j >= d.half;
    d.x = i - d.type_x * d.half, d.y = j - d.type_y * d.half;
    return d;
}

SquareMeans::SquareMeans(int n) : n_(n), per_face_(size_t(level_offset(n))), means_(6 * per_face_) {
    RSL_CHECK(haar::is_power_of_two(n));
}

void SquareMeans::build(const Color* texels) {
    const int n = n_;
    for (int face = 0; face < 6; ++face) {
        const Color* t = texels + size_t(face) * n * n;
        Color* m = means_.data() + size_t(face) * per_face_;
        if (n < 2) continue;
        // Finest squares (side 2) from the texels, then each level from its children.
        const int finest = n / 2;
        Color* level = m + level_offset(finest);
        for (int y = 0; y < finest; ++y)
            for (int x = 0; x < finest; ++x)
                level[y * finest + x] = 0.25f * (t[(2 * y) * n + 2 * x] + t[(2 * y) * n + 2 * x + 1] +
                                                 t[(2 * y + 1) * n + 2 * x] + t[(2 * y + 1) * n + 2 * x + 1]);
        for (int half = finest / 2; half >= 1; half /= 2) {
            const Color* child = m + level_offset(2 * half);
            Color* parent = m + level_offset(half);
            const int c = 2 * half;
            for (int y = 0; y < half; ++y)
                for (int x = 0; x < half; ++x)
                    parent[y * half + x] = 0.25f * (child[(2 * y) * c + 2 * x] + child[(2 * y) * c + 2 * x + 1] +
                                                    child[(2 * y + 1) * c + 2 * x] + child[(2 * y + 1) * c + 2 * x + 1]);
        }
    }
}

PreparedLighting::PreparedLighting(int n)
    : n_(n), dense_(size_t(6) * n * n), texels_(size_t(6) * n * n), scratch_(size_t(n) * n * 3), means_(n) {}

void PreparedLighting::prepare(const int32_t* index, const Color* value, size_t terms) {
    const int n = n_;
    index_.assign(index, index + terms);
    value_.assign(value, value + terms);
    detail_.resize(terms), sibling_a_.resize(terms), sibling_b_.resize(terms), inverse_side_.resize(terms);
    std::fill(dense_.begin(), dense_.end(), Color(0.0f));
    for (size_t t = 0; t < terms; ++t) {
        const Detail d = decode(index[t], n);
        detail_[t] = d;
        dense_[size_t(index[t])] = value[t];
        inverse_side_[t] = float(d.half) / float(n);
        // The square's two other detail types, in the order h, v, g.
        int found = 0, others[2] = {-1, -1};
        for (const auto& [tx, ty] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}})
            if (d.half > 0 && (tx != d.type_x || ty != d.type_y))
                others[found++] = d.face_base + (d.y + ty * d.half) * n + d.x + tx * d.half;
        sibling_a_[t] = others[0], sibling_b_[t] = others[1];
    }
    // The kept terms' reconstruction, for the means of L over squares.
    for (int face = 0; face < 6; ++face) {
        float* data = reinterpret_cast<float*>(texels_.data() + size_t(face) * n * n);
        std::copy_n(reinterpret_cast<const float*>(dense_.data() + size_t(face) * n * n), size_t(n) * n * 3, data);
        haar::inverse_face(data, n, 3, scratch_.data());
    }
    means_.build(texels_.data());
}

Color evaluate(const PreparedLighting& lighting, const Factors& f) {
    const int n = lighting.n_;
    const float* V = f.visibility_dense;
    const Color* rho = f.brdf_dense;
    DVec3 sum(0.0);
    // 1. φ φ φ, per face.
    for (int face = 0; face < 6; ++face) {
        const int base = face * n * n;
        sum += DVec3(lighting.dense_[base] * (V[base] / float(n)) * rho[base]);
    }
    // 2. and 3. with a lighting detail: the square's other two types, and the
    // pairs (L, V) and (L, ρ̃) times the third's mean over the square.
    for (size_t t = 0; t < lighting.index_.size(); ++t) {
        const Detail& d = lighting.detail_[t];
        if (d.half == 0) continue;
        const int i = lighting.index_[t], a = lighting.sibling_a_[t], b = lighting.sibling_b_[t];
        Color term = (V[a] * rho[b] + V[b] * rho[a]) * lighting.inverse_side_[t];
        if (V[i] != 0.0f) term += V[i] * ancestor_mean(rho + d.face_base, n, d);
        if (nonzero(rho[i])) term += rho[i] * ancestor_mean(V + d.face_base, n, d);
        sum += DVec3(lighting.value_[t] * term);
    }
    // 3. the pairs (V, ρ̃) times L's mean over the square, over the sparser list.
    if (f.brdf_index && f.brdf_count < f.visibility_count) {
        for (size_t e = 0; e < f.brdf_count; ++e) {
            const int i = f.brdf_index[e];
            if (V[i] == 0.0f) continue;
            const Detail d = decode(i, n);
            if (d.half > 0) sum += DVec3(rho[i] * V[i] * lighting.means_.mean(d));
        }
    } else {
        for (size_t e = 0; e < f.visibility_count; ++e) {
            const int i = int(f.visibility_index[e]);
            if (!nonzero(rho[i])) continue;
            const Detail d = decode(i, n);
            if (d.half > 0) sum += DVec3(rho[i] * V[i] * lighting.means_.mean(d));
        }
    }
    return Color(sum);
}

}  // namespace rsl::triple
