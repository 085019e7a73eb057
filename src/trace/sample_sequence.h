#pragma once
// Random numbers for Monte Carlo estimators that give the same answer at any
// thread count: every number is a hash of (seed, stream, sample index,
// dimension), never a generator's state (docs/BASELINES.md, "env-rays").
//
// Stratified points are a 2D Sobol sequence, Owen-scrambled with the hash
// of Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020): the first
// 2^m points of every scramble are a (0, m, 2)-net (one point in every
// elementary interval of area 2^-m), and each point alone is uniform in
// [0, 1)², so an estimator that uses them stays unbiased.
#include <cstdint>

namespace rsl {

// splitmix64's finalizer: 64 well-mixed bits of any 64-bit input.
inline uint64_t mix64(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// The bits of sample `index`, dimension `dimension` of stream `stream`.
inline uint64_t sample_bits(uint64_t seed, uint64_t stream, uint32_t index, uint32_t dimension) {
    return mix64(mix64(mix64(seed) ^ stream) ^ ((uint64_t(index) << 32) | dimension));
}

// 32 bits → [0, 1): every value below 1, so an inverse CDF never runs off its end.
inline double unit_from_bits(uint32_t bits) { return double(bits) * (1.0 / 4294967296.0); }
inline double unit_from_bits(uint64_t bits) { return double(bits >> 11) * (1.0 / 9007199254740992.0); }

inline uint32_t reverse_bits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

// A random permutation of [0, 2^32) in which every bit depends only on the
// bits below it (adding and multiplying by even numbers carry upwards only).
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

// Owen's nested uniform scrambling of a binary fraction (bit 31 = ½): each
// digit flipped by a hash of the digits above it.
inline uint32_t owen_scramble(uint32_t x, uint32_t seed) {
    return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// The first two Sobol dimensions: van der Corput, and the one whose
// direction numbers are the rows of Pascal's triangle mod 2.
inline uint32_t sobol_dimension0(uint32_t index) { return reverse_bits(index); }
inline uint32_t sobol_dimension1(uint32_t index) {
    uint32_t x = 0;
    for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
        if (index & 1u) x ^= v;
    return x;
}

// sobol_dimension1 in reversed bit order, without a loop over the index's
// bits: digit d of point k is C(k, d) mod 2, which by Lucas' theorem is 1
// exactly when d's bits are a subset of k's, so the digits are the XOR over
// the supersets of each bit position: a subset-sum transform in 5 steps.
inline uint32_t sobol_dimension1_reversed(uint32_t index) {
    index ^= (index >> 1) & 0x55555555u;
    index ^= (index >> 2) & 0x33333333u;
    index ^= (index >> 4) & 0x0f0f0f0fu;
    index ^= (index >> 8) & 0x00ff00ffu;
    index ^= (index >> 16) & 0x0000ffffu;
    return index;
}

struct UnitPair {
    double u0 = 0, u1 = 0;
};

// The Owen-scrambled, shuffled 2D Sobol sequence of one (seed, stream,
// dimension): its three scramble seeds (the shuffle and each axis) hashed
// once, then any point. owen_scramble(reverse_bits(x)) is
// reverse_bits(laine_karras_permutation(x)), so each axis costs one
// permutation and one bit reversal.
class ScrambledSobol {
public:
    ScrambledSobol(uint64_t seed, uint64_t stream, uint32_t dimension) {
        const uint64_t seeds = sample_bits(seed, stream, 0xffffffffu, dimension);
        shuffle_seed_ = uint32_t(seeds), seed0_ = uint32_t(seeds >> 32), seed1_ = uint32_t(mix64(seeds) >> 32);
    }
    UnitPair point(uint32_t index) const {
        const uint32_t shuffled = owen_scramble(index, shuffle_seed_);
        return {unit_from_bits(reverse_bits(laine_karras_permutation(shuffled, seed0_))),
                unit_from_bits(reverse_bits(laine_karras_permutation(sobol_dimension1_reversed(shuffled), seed1_)))};
    }

private:
    uint32_t shuffle_seed_ = 0, seed0_ = 0, seed1_ = 0;
};

// Point `index` of ScrambledSobol(seed, stream, dimension), by the
// definitions (Sobol digits, then owen_scramble): what ScrambledSobol must equal.
inline UnitPair scrambled_sobol(uint64_t seed, uint64_t stream, uint32_t index, uint32_t dimension) {
    const uint64_t seeds = sample_bits(seed, stream, 0xffffffffu, dimension);
    const uint32_t shuffled = owen_scramble(index, uint32_t(seeds));
    const uint32_t axis_seeds = uint32_t(mix64(seeds) >> 32);
    return {unit_from_bits(owen_scramble(sobol_dimension0(shuffled), uint32_t(seeds >> 32))),
            unit_from_bits(owen_scramble(sobol_dimension1(shuffled), axis_seeds))};
}

// Two independent uniforms (the unstratified estimator, for comparison).
inline UnitPair independent_pair(uint64_t seed, uint64_t stream, uint32_t index, uint32_t dimension) {
    const uint64_t bits = sample_bits(seed, stream, index, dimension);
    return {unit_from_bits(uint32_t(bits)), unit_from_bits(uint32_t(bits >> 32))};
}

}  // namespace rsl
