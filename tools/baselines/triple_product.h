#pragma once
// Triple products of cube-map functions in the non-standard Haar basis of
// haar.h (Ng, Ramamoorthi, Hanrahan 2004, "Triple product wavelet
// integrals"): Σ_k a_k b_k c_k from the three functions' coefficients.
//
// Per face of side N the tripling coefficient C_ijl = Σ_k ψ_i ψ_j ψ_l is
// non-zero only when (Ng 2004's theorem, with haar.h's sign patterns)
//   1. all three are the face's scaling function φ = 1/N:           C = 1/N;
//   2. they are the three distinct details h, v, g of one square S
//      of side s (the product of their signs is + on every texel):  C = 1/s;
//   3. two are the same detail of S and the third is φ or a detail
//      of a strictly coarser square containing S: C = that third function's
//      value on S. Summed over the third function's coefficients this is
//      the third function's mean over S's texels.
// Every other triple (φ φ ψ, φ ψ ψ′, ψ ψ ψ, nested or disjoint squares)
// integrates a zero-mean pattern over the finest support and vanishes. So
//
//   Σ_k a b c = Σ_faces [ a_φ b_φ c_φ / N
//                        + Σ_S (1/s) Σ_{perm(h,v,g)} a b c
//                        + Σ_details i (a_i b_i mean_S(c) + a_i c_i mean_S(b) + b_i c_i mean_S(a)) ].
//
// Here a = the lighting L (a few kept terms, RGB), b = the visibility times
// the texel solid angles V·Ω (one channel), c = the BRDF slice ρ̃ (RGB). The
// evaluation walks L's terms and the sparser of b's and c's lists, and looks
// the others up in dense scratch arrays: O((N_L + nnz)·log N) per vertex.
#include <cstdint>
#include <vector>

#include "src/core/math.h"

namespace rsl::triple {

// A detail coefficient's place: its square (x, y) at level `half` (the
// square's side is N / half), its face's first index and its type bits.
struct Detail {
    int face_base = 0;  // face · N²
    int half = 0;       // 0 for the scaling coefficient φ
    int x = 0, y = 0;
    int type_x = 0, type_y = 0;  // h = (1, 0), v = (0, 1), g = (1, 1)
};
Detail decode(int index, int n);

// Means of a texel function over every square of the Haar pyramid (the
// squares of the details at every level), per face.
class SquareMeans {
public:
    explicit SquareMeans(int n);
    // From texel values (6N², RGB). No allocation.
    void build(const Color* texels);
    Color mean(const Detail& d) const {
        const size_t face = size_t(d.face_base / (n_ * n_));
        return means_[face * per_face_ + size_t(level_offset(d.half) + d.y * d.half + d.x)];
    }
    int resolution() const { return n_; }

private:
    static int level_offset(int half) { return (half * half - 1) / 3; }
    int n_;
    size_t per_face_;
    std::vector<Color> means_;
};

// One vertex's other two factors: each a list of its non-zero coefficients
// and the same values scattered into a dense 6N² array (zero elsewhere).
// A null list means "dense": every index may be non-zero.
struct Factors {
    const float* visibility_dense = nullptr;
    const uint32_t* visibility_index = nullptr;
    size_t visibility_count = 0;
    const Color* brdf_dense = nullptr;
    const int32_t* brdf_index = nullptr;  // null: dense
    size_t brdf_count = 0;
};

// The lighting's kept terms, decoded once per frame (structure of arrays),
// with the sparse lighting scattered densely and its square means.
class PreparedLighting {
public:
    explicit PreparedLighting(int n);
    // `index`/`value`: the kept coefficients (cube indices); no allocation
    // after the first call with as many terms.
    void prepare(const int32_t* index, const Color* value, size_t terms);
    int resolution() const { return n_; }
    size_t terms() const { return index_.size(); }

private:
    friend Color evaluate(const PreparedLighting&, const Factors&);
    int n_;
    std::vector<int32_t> index_, sibling_a_, sibling_b_;
    std::vector<Color> value_;
    std::vector<Detail> detail_;
    std::vector<float> inverse_side_;
    std::vector<Color> dense_;    // 6N², zero but at the kept terms
    std::vector<Color> texels_;   // the kept terms' reconstruction
    std::vector<float> scratch_;
    SquareMeans means_;
};

// Σ_k L_k (VΩ)_k ρ̃_k by the tripling coefficients. No allocation.
Color evaluate(const PreparedLighting& lighting, const Factors& factors);

}  // namespace rsl::triple
