#pragma once
// The interpolation taps every table lookup shares: a pair of samples with
// the upper one's weight, and the four bilinear taps of an n×n table.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// Linear interpolation between two neighbouring samples (or SAT corners,
// or shells): the lower one, and the upper one's weight.
struct LerpPair {
    int lower;
    float upper_weight;
};
// Between `count` ≥ 2 samples at positions 0, 1, …, count − 1: position t
// clamped to the first and last sample.
RSL_SHARED LerpPair sample_lerp(float t, int count) {
    float x = clamp(t, 0.0f, float(count - 1));
    LerpPair s;
    s.lower = min(int(x), count - 2);
    s.upper_weight = x - float(s.lower);
    return s;
}

// Bilinear taps between texel centres of an n×n table over [-1, 1]²; the
// edge value is held outside the outermost centres. Texels (i, j), (i+1, j),
// (i, j+1), (i+1, j+1), stored at j·n + i.
struct BilinearTaps {
    ivec4 index;
    vec4 weight;
};
RSL_SHARED BilinearTaps bilinear_taps(int n, vec2 p) {
    float hi = float(n - 1);
    float u = clamp((p.x + 1.0f) * (0.5f * float(n)) - 0.5f, 0.0f, hi);
    float v = clamp((p.y + 1.0f) * (0.5f * float(n)) - 0.5f, 0.0f, hi);
    int i0 = min(int(u), n - 2);
    int j0 = min(int(v), n - 2);
    float fx = u - float(i0);
    float fy = v - float(j0);
    int base = j0 * n + i0;
    BilinearTaps taps;
    taps.index = ivec4(base, base + 1, base + n, base + n + 1);
    taps.weight = vec4((1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy);
    return taps;
}

// RSL_GLSL_END

}  // namespace rsl::shading
