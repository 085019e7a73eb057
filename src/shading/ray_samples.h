#pragma once
// The ray-traced baseline's rays (docs/BASELINES.md "Many lights"): where
// each of a vertex's S×S jittered rays towards a light's square points, and
// how far off the surface rays start. The CPU's Embree rows
// (src/render/exact_visibility.h) and the GPU's compute-shader rows both
// call these, so that the two trace the same rays from the same seeds.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// 64-bit unsigned integers as (low word, high word): GLSL 330 has no uint64.
RSL_SHARED uvec2 add64(uvec2 a, uvec2 b) {
    uint low = a.x + b.x;
    return uvec2(low, a.y + b.y + (low < a.x ? 1u : 0u));
}

// The whole 64-bit product of two 32-bit words, from their 16-bit halves.
RSL_SHARED uvec2 wide_multiply(uint a, uint b) {
    uint a0 = a & 0xffffu;
    uint a1 = a >> 16;
    uint b0 = b & 0xffffu;
    uint b1 = b >> 16;
    uint low = a0 * b0;
    uint cross1 = a1 * b0;
    uint cross2 = a0 * b1;
    uint middle = (low >> 16) + (cross1 & 0xffffu) + (cross2 & 0xffffu);
    return uvec2((low & 0xffffu) | (middle << 16), a1 * b1 + (cross1 >> 16) + (cross2 >> 16) + (middle >> 16));
}

// a·b mod 2⁶⁴.
RSL_SHARED uvec2 multiply64(uvec2 a, uvec2 b) {
    uvec2 p = wide_multiply(a.x, b.x);
    return uvec2(p.x, p.y + a.x * b.y + a.y * b.x);
}

// z ^ (z >> s) for 0 < s < 32.
RSL_SHARED uvec2 xor_shift64(uvec2 z, int s) {
    return uvec2(z.x ^ ((z.x >> s) | (z.y << (32 - s))), z.y ^ (z.y >> s));
}

// splitmix64: a stateless hash to uniform bits, so that a ray's direction
// does not depend on which thread or workgroup traces it.
RSL_SHARED uvec2 splitmix64(uvec2 z) {
    z = add64(z, uvec2(0x7f4a7c15u, 0x9e3779b9u));
    z = multiply64(xor_shift64(z, 30), uvec2(0x1ce4e5b9u, 0xbf58476du));
    z = multiply64(xor_shift64(z, 27), uvec2(0x133111ebu, 0x94d049bbu));
    return xor_shift64(z, 31);
}

// The seed of the rays of light `light` at vertex `vertex` of part `part`.
RSL_SHARED uvec2 ray_seed(int part, int vertex, int light) {
    uvec2 l = splitmix64(uvec2(uint(light), 0u));
    return splitmix64(uvec2(uint(vertex) ^ l.x, uint(part) ^ l.y));
}

// Where in its cell jittered sample k of `seed` lies: (u, v) in [0, 1)²,
// 24 bits each of splitmix64(seed + k).
RSL_SHARED vec2 jitter_in_cell(uvec2 seed, int k) {
    uvec2 bits = splitmix64(add64(seed, uvec2(uint(k), 0u)));
    uint u = bits.y >> 8;
    uint v = ((bits.x >> 16) | (bits.y << 16)) & 0xffffffu;
    return vec2(float(u), float(v)) * (1.0f / 16777216.0f);
}

// Point (i, j) of an S×S grid over the square (plane centre c, half-edge
// h), at `in_cell` within its cell ((½, ½): the cell's centre).
RSL_SHARED vec2 square_grid_point(vec2 c, float h, int samples, int i, int j, vec2 in_cell) {
    float cell = 2.0f / float(samples);
    return c + h * vec2((float(i) + in_cell.x) * cell - 1.0f, (float(j) + in_cell.y) * cell - 1.0f);
}

// How far off its surface a ray leaving point p starts (docs/design/TRUTH.md
// "Ray offsets"): a fraction of its part's posed size (`scale`: the part's
// box diagonal) plus a few float ULPs of |p|.
RSL_CONST float kRayOffsetOfScale = 1e-5f;
RSL_CONST float kRayOffsetOfPosition = 1.0f / 131072.0f;  // 2⁻¹⁷ ≈ 64 ULPs
RSL_SHARED float ray_offset_distance(float scale, vec3 p) {
    float coord = max(abs(p.x), max(abs(p.y), abs(p.z)));
    return kRayOffsetOfScale * scale + kRayOffsetOfPosition * coord;
}

// An occlusion query from a surface ignores a hit that leaves its triangle
// through the front within this many ray offsets (of the hit part's scale and
// of the origin's position) of the origin: the origin lies on that surface
// (RayScene's origins_outside_surfaces; docs/design/TRUTH.md "Ray offsets").
RSL_CONST float kRayExitOffsets = 4.0f;

// RSL_GLSL_END

}  // namespace rsl::shading
