#pragma once
// Occluders of exact shape, flat rectangles and boxes
// (src/render/occluder_shape.h; docs/design/RENDERER.md "Occluders of exact shape").
#include "src/shading/frames.h"
#include "src/shading/shadow_maps.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// A ground or a wall is one flat rectangle, and its shadow is known exactly:
// a ray leaves the receiver and crosses the rectangle's plane or not. Its
// OVDF, sampled on shells, blends samples from both sides of the plane and
// comes out far too dark near it (docs/design/RENDERER.md, "Occluders of exact shape").
// Coordinates are the rectangle's own: (s, t) across it from its centre,
// height along its normal; the rectangle is |s| ≤ half.x, |t| ≤ half.y.

// How far (× the shape's size) a receiver may lie from a face and still
// count as on it. A vertex resting on the ground lands a few float ULPs above
// or below the plane once posed, differently on the CPU and the GPU; without
// the margin the two renderers would shadow it from opposite sides.
RSL_CONST float kShapeContactMargin = 1e-5f;

// Whether a receiver is on the side of the rectangle its normal faces. One
// on the plane (a part resting on the ground; within the contact margin)
// counts as above it.
RSL_SHARED bool above_rectangle(vec3 point, vec2 half_extent) {
    return point.z >= -kShapeContactMargin * (half_extent.x + half_extent.y);
}
// Whether the ray from `point` along `dir` (any length; an affine map of
// both keeps the answer) crosses the rectangle.
RSL_SHARED bool planar_blocks(vec3 point, vec3 dir, vec2 half_extent) {
    // Written without branches (two compares), so that the taps' loop in
    // shape_visible_fraction vectorizes on the CPU.
    float toward = above_rectangle(point, half_extent) ? -dir.z : dir.z;
    float t = -point.z / dir.z;
    float s = point.x + t * dir.x;
    float u = point.y + t * dir.y;
    float across = max(abs(s) - half_extent.x, abs(u) - half_extent.y);  // ≤ 0: inside the rectangle
    return toward > 0.0f && across <= 0.0f;
}
// The box as the slab test sees it from one point: its bounds shrunk by the
// contact margin, and per axis the entry of a ray parallel to that slab (0
// inside it; outside it, past any exit: the ray misses). Computed once per
// point, so that the per-tap test below has no branch and vectorizes.
struct BoxSlabs {
    vec3 low;
    vec3 high;
    vec3 parallel_entry;
};
RSL_SHARED BoxSlabs box_slabs(vec3 point, vec3 lo, vec3 hi) {
    float margin = kShapeContactMargin * length(hi - lo);
    BoxSlabs s;
    s.low = lo + vec3(margin);
    s.high = hi - vec3(margin);
    for (int a = 0; a < 3; ++a) s.parallel_entry[a] = point[a] < s.low[a] || point[a] > s.high[a] ? 3.0e38f : 0.0f;
    return s;
}
RSL_SHARED bool slabs_block(vec3 point, vec3 dir, BoxSlabs s) {
    float entry = 0.0f;
    float exit = 3.0e38f;
    for (int a = 0; a < 3; ++a) {
        bool parallel = dir[a] == 0.0f;
        float along = parallel ? 1.0f : dir[a];
        float t0 = (s.low[a] - point[a]) / along;
        float t1 = (s.high[a] - point[a]) / along;
        entry = max(entry, parallel ? s.parallel_entry[a] : min(t0, t1));
        exit = parallel ? exit : min(exit, max(t0, t1));
    }
    return exit > entry;
}
// Whether the ray from `point` along `dir` passes through the inside of the
// box [lo, hi] (the slab test), the box shrunk by the contact margin: a ray
// that starts on a face and leaves it is free, one that enters is blocked,
// so a part resting on a box is shadowed by it only where it really is.
RSL_SHARED bool box_blocks(vec3 point, vec3 dir, vec3 lo, vec3 hi) {
    return slabs_block(point, dir, box_slabs(point, lo, hi));
}
// Interval arithmetic for the whole-square test below: the range of a·x
// over x ∈ [lo, hi], and of x·y over two intervals.
RSL_SHARED vec2 scaled_range(float a, vec2 r) { return vec2(min(a * r.x, a * r.y), max(a * r.x, a * r.y)); }
RSL_SHARED vec2 product_range(vec2 a, vec2 b) {
    float p0 = a.x * b.x;
    float p1 = a.x * b.y;
    float p2 = a.y * b.x;
    float p3 = a.y * b.y;
    return vec2(min(min(p0, p1), min(p2, p3)), max(max(p0, p1), max(p2, p3)));
}
RSL_SHARED vec2 square_range(vec2 r) {  // of x² over x ∈ r
    float a = r.x * r.x;
    float b = r.y * r.y;
    return vec2(r.x <= 0.0f && r.y >= 0.0f ? 0.0f : min(a, b), max(a, b));
}
// Bounds on the directions (in the shape's coordinates) of the square's
// taps that count: those above the receiver's horizon, whose plane radius²
// is at most reach2 (< 1). Each coordinate's least and greatest value, by
// interval arithmetic over the square (plane_to_hemisphere of each
// coordinate range) cut at radius² reach2, widened by a relative margin for
// the taps' own rounding. So a whole-square answer drawn from them is the one
// every tap would give. The cut matters: bounded at the horizon itself (1),
// a square straddling the horizon of an upward-facing receiver reached
// "down" by the margin and ran every tap to find them all lit (in the yard,
// 57k of the 210k such ground lookups a frame).
struct SquareDirections {
    vec3 lo;
    vec3 hi;
};
RSL_SHARED SquareDirections square_directions(LocalFrame frame, vec2 c, float h, float reach2) {
    SquareDirections d;
    vec2 qx = vec2(c.x - h, c.x + h);
    vec2 qy = vec2(c.y - h, c.y + h);
    vec2 r2 = square_range(qx) + square_range(qy);
    r2.y = min(r2.y, reach2);
    r2.x = min(r2.x, r2.y);
    vec2 root = vec2(sqrt(2.0f - r2.y), sqrt(2.0f - r2.x));
    vec2 wx = product_range(qx, root);
    vec2 wy = product_range(qy, root);
    vec2 wz = vec2(1.0f - r2.y, 1.0f - r2.x);
    vec2 dx = scaled_range(frame.x.x, wx) + scaled_range(frame.y.x, wy) + scaled_range(frame.z.x, wz);
    vec2 dy = scaled_range(frame.x.y, wx) + scaled_range(frame.y.y, wy) + scaled_range(frame.z.y, wz);
    vec2 dz = scaled_range(frame.x.z, wx) + scaled_range(frame.y.z, wy) + scaled_range(frame.z.z, wz);
    float margin = 1e-4f * (length(frame.x) + length(frame.y) + length(frame.z));
    d.lo = vec3(dx.x, dy.x, dz.x) - vec3(margin);
    d.hi = vec3(dx.y, dy.y, dz.y) + vec3(margin);
    return d;
}
// Whether a rectangle decides a whole square at once: 1 when every direction
// of the square's part above the receiver's horizon leaves the plane, 0 when
// every one reaches it inside the rectangle, −1 when the taps must decide.
// A ground under an object decides most (vertex, light) pairs with no tap at all.
RSL_SHARED float rectangle_decides_square(vec3 point, SquareDirections d, vec2 half_extent) {
    bool above = above_rectangle(point, half_extent);
    // Towards the plane: down from above it, up from below.
    vec2 toward = above ? vec2(-d.hi.z, -d.lo.z) : vec2(d.lo.z, d.hi.z);
    if (toward.y < 0.0f) return 1.0f;  // every direction leaves the plane
    if (!(toward.x > 0.0f)) return -1.0f;
    // Every direction reaches the plane at t = |height| / |d.z| ≤ |height| / toward.x,
    // across by at most t·|d.x| and t·|d.y|.
    float t = abs(point.z) / toward.x;
    float across_x = t * max(abs(d.lo.x), abs(d.hi.x));
    float across_y = t * max(abs(d.lo.y), abs(d.hi.y));
    bool inside = abs(point.x) + across_x < half_extent.x * (1.0f - 1e-4f) &&
                  abs(point.y) + across_y < half_extent.y * (1.0f - 1e-4f);
    return inside ? 0.0f : -1.0f;
}
// The same for a box (box_blocks' box, shrunk by the contact margin): 1 when
// the receiver is on or beyond a face that every direction leaves; 0 when
// every direction enters the box through the inside of one face; else −1.
RSL_SHARED float box_decides_square(vec3 point, SquareDirections d, vec3 lo, vec3 hi) {
    float margin = kShapeContactMargin * length(hi - lo);
    vec3 low = lo + vec3(margin);
    vec3 high = hi - vec3(margin);
    for (int a = 0; a < 3; ++a) {
        if (point[a] >= high[a] && d.lo[a] > 0.0f) return 1.0f;
        if (point[a] <= low[a] && d.hi[a] < 0.0f) return 1.0f;
    }
    for (int a = 0; a < 3; ++a) {
        // The face the directions cross first, and when: t ∈ [t.x, t.y].
        vec2 t = vec2(-1.0f);
        if (point[a] < low[a] && d.lo[a] > 0.0f) t = vec2(low[a] - point[a]) / vec2(d.hi[a], d.lo[a]);
        if (point[a] > high[a] && d.hi[a] < 0.0f) t = vec2(high[a] - point[a]) / vec2(d.lo[a], d.hi[a]);
        // A face seen edge-on from far away: the slab test's entry and exit
        // could round to one value.
        if (!(t.x > 0.0f) || high[a] - low[a] < 1e-3f * abs(point[a] - low[a])) continue;
        bool inside = true;
        for (int b = 0; b < 3; ++b) {
            if (b == a) continue;
            vec2 across = vec2(point[b]) + product_range(t, vec2(d.lo[b], d.hi[b]));
            float slack = 1e-4f * (high[b] - low[b]);
            inside = inside && across.x > low[b] + slack && across.y < high[b] - slack;
        }
        if (inside) return 0.0f;
    }
    return -1.0f;
}

// The exact shapes' kinds (kSlotShape in gpu_layout.h).
RSL_CONST int kShapeNone = 0;
RSL_CONST int kShapeRectangle = 1;  // lo, hi = (−half s, −half t, 0), (half s, half t, 0)
RSL_CONST int kShapeBox = 2;
// The shape's tap loops run over kShadowTaps rounded up to a multiple of 8.
RSL_CONST int kShapeTapLanes = (kShadowTaps + 7) / 8 * 8;
// Plane radius of a tap pulled in to just above the horizon (elevation ≈ 0.1°).
RSL_CONST float kHorizonTapRadius = 0.999f;
// Tap i of a shape's filter: 1 when it is above the receiver's horizon, and
// its direction in the shape's coordinates; one below the horizon is pulled
// in to just above it (it counts only when no tap is above).
RSL_SHARED int shape_tap_above(vec2 c, float h, int i) {
    vec2 tap = shadow_tap_point(c, h, i);
    return dot(tap, tap) < 1.0f ? 1 : 0;
}
RSL_SHARED vec3 shape_tap_direction(LocalFrame frame, vec2 c, float h, int i) {
    vec2 tap = shadow_tap_point(c, h, i);
    float r2 = dot(tap, tap);
    tap = r2 >= 1.0f ? tap * (kHorizonTapRadius / sqrt(r2)) : tap;
    return frame_to_world(frame, plane_to_hemisphere(tap));
}
// The visible share of the square (plane centre c, half-edge h) of a
// receiver whose shading frame has axes `frame` (in the shape's coordinates)
// against a rectangle or a box: the filter taps above the receiver's horizon
// (as the shadow maps' shadow_tap_point) whose rays miss it. A square that
// only grazes the hemisphere between its taps still has a BRDF average
// (a sandwiched vertex lit by the one light low on its horizon was the
// bug): then every tap counts, pulled in to just above the horizon.
RSL_SHARED float shape_visible_fraction(int shape, vec3 point, LocalFrame frame, vec2 c, float h, vec3 lo, vec3 hi) {
    // The taps above the horizon, and the farthest one's plane radius².
    vec2 r2 = square_range(vec2(c.x - h, c.x + h)) + square_range(vec2(c.y - h, c.y + h));
    int above = kShadowTaps;
    float reach2 = r2.y;
    if (!(r2.y < 1.0f - 1e-5f)) {  // some tap may be below the horizon (a margin for the taps' rounding)
        // Two loops: the taps' radii² first, which vectorizes on the CPU (the
        // maximum's reduction alone would keep the taps' own arithmetic,
        // divisions included, scalar: a quarter of this function's time in
        // the yard-128's profile).
        float tap_r2[kShadowTaps];
        for (int i = 0; i < kShadowTaps; ++i) {
            vec2 tap = shadow_tap_point(c, h, i);
            tap_r2[i] = dot(tap, tap);
        }
        above = 0;
        reach2 = 0.0f;
        for (int i = 0; i < kShadowTaps; ++i) {
            above += tap_r2[i] < 1.0f ? 1 : 0;
            reach2 = max(reach2, tap_r2[i] < 1.0f ? tap_r2[i] : 0.0f);
        }
    }
    if (above > 0) {
        SquareDirections d = square_directions(frame, c, h, reach2);
        float whole = shape == kShapeBox ? box_decides_square(point, d, lo, hi)
                                         : rectangle_decides_square(point, d, vec2(hi.x, hi.y));
        if (whole >= 0.0f) return whole;
    }
    // One loop per shape, each tap without branches (two integer sums, of
    // the taps above the horizon and of all), so that the CPU's loops
    // vectorize over the taps.
    int lit_above = 0;
    int lit_all = 0;
    // Over kShapeTapLanes, the taps past kShadowTaps counting for nothing:
    // the CPU's 16-wide loop then ends in an 8-wide one, not in five scalar
    // taps (a fifth of this function's time in the yard-128's profile).
    if (shape == kShapeBox) {
        BoxSlabs slabs = box_slabs(point, lo, hi);
        for (int i = 0; i < kShapeTapLanes; ++i) {
            int lit = (i < kShadowTaps ? 1 : 0) * (slabs_block(point, shape_tap_direction(frame, c, h, i), slabs) ? 0 : 1);
            lit_above += shape_tap_above(c, h, i) * lit;
            lit_all += lit;
        }
    } else {
        for (int i = 0; i < kShapeTapLanes; ++i) {
            int lit = (i < kShadowTaps ? 1 : 0) *
                      (planar_blocks(point, shape_tap_direction(frame, c, h, i), vec2(hi.x, hi.y)) ? 0 : 1);
            lit_above += shape_tap_above(c, h, i) * lit;
            lit_all += lit;
        }
    }
    return above > 0 ? float(lit_above) / float(above) : float(lit_all) / float(kShadowTaps);
}

// RSL_GLSL_END

}  // namespace rsl::shading
