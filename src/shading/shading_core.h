// The one shading core of the CPU and GPU renderers: every pure
// per-vertex × per-light function of the rendering sum (docs/RENDERER.md,
// docs/GPU.md), written once in the common subset of C++ (glm) and GLSL 330.
//
// C++ includes this header (namespace rsl::shading; the older names stay
// visible in rsl through using-declarations in hemisphere.h, vdt.h, ovdf.h,
// square_lights.h). The GPU gets the text between the two GLSL markers below:
// src/gl/embed_shaders_script.cmake embeds it as "shading_core.glsl", and
// gl_objects.cpp prepends it, after the layout constants generated from
// src/gl/gpu_layout.h (kPi, kSqrt2 among them), to the shading pass. So a
// formula changed here changes both renderers; tests/gl/shading_core_test.cpp
// runs every function below on both and compares.
//
// What stays per side is data access (pointers and SoA loops on the CPU,
// texelFetch on the GPU) and the CPU's vectorized batch kernels.
//
// Rules of the shared part, so that it compiles as both languages:
//  * glm type names (vec2, vec3, vec4, ivec4), functions of both libraries
//    (min, max, clamp, abs, sqrt, log, sin, dot, length, normalize, cross), no
//    swizzles;
//  * results are small structs filled member by member (GLSL has no
//    aggregate initializers; C++ has no `out` parameters): no references,
//    pointers, templates, overloads on constness or member initializers;
//  * float literals carry `f` (GLSL ≥ 1.30 accepts it), locals are not
//    `const` (GLSL 330 wants constant initializers there);
//  * RSL_SHARED before every function (C++: inline), RSL_CONST before
//    constants (C++: inline constexpr; GLSL: const).
#pragma once
#include <bit>
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

#define RSL_SHARED inline
#define RSL_CONST inline constexpr

namespace rsl::shading {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::length;
using glm::max;
using glm::min;
using glm::normalize;
using std::abs;
using std::log;
using std::sin;
using std::sqrt;

// GLSL's bit reinterpretations (portable_log).
inline int floatBitsToInt(float x) { return std::bit_cast<int>(x); }
inline float intBitsToFloat(int x) { return std::bit_cast<float>(x); }

// π and √2 come from std::numbers; the GPU gets these values as generated
// constants (gpu_layout.h shader_constants_glsl), not as literals.
inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kSqrt2 = std::numbers::sqrt2_v<float>;

// RSL_GLSL_BEGIN (the GPU's copy starts here)

// Value of a visibility distance table whose map has no boundary (all
// visible or all blocked), plane units: more than any square's half-edge.
RSL_CONST float kVdtNoBoundaryDistance = 4.0f;
// Where an OVDF's bounding cone edge lies in a zoomed table ([-1, 1]²).
RSL_CONST float kOvdfZoomEdge = 0.75f;
// The cone radius used where there is no cone (inside the bounding sphere).
RSL_CONST float kOvdfNoCone = 1e6f;
RSL_CONST int kCubeFaces = 6;

// ---- frames and the equal-area map (src/core/hemisphere.h) ----

// Any unit vector orthogonal to n (Duff et al. 2017, branchless ONB).
RSL_SHARED vec3 any_orthonormal(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}

// Local frame: z = the normal, x = the tangent orthogonalized (Gram–Schmidt),
// any orthonormal x when the tangent is missing or parallel, y = z × x.
struct LocalFrame {
    vec3 x;
    vec3 y;
    vec3 z;
};
RSL_SHARED LocalFrame frame_from_normal_tangent(vec3 n, vec3 t) {
    LocalFrame f;
    f.z = normalize(n);
    vec3 x = t - f.z * dot(f.z, t);
    float len2 = dot(x, x);
    f.x = len2 > 1e-12f ? x * (1.0f / sqrt(len2)) : any_orthonormal(f.z);  // one division, not three
    f.y = cross(f.z, f.x);
    return f;
}
RSL_SHARED vec3 frame_to_local(LocalFrame f, vec3 v) { return vec3(dot(v, f.x), dot(v, f.y), dot(v, f.z)); }

// Local direction (unit, anywhere but the exact antipode) → plane point
// p = (x, y) / √(1 + z), Lambert's azimuthal equal-area map.
RSL_SHARED vec2 hemisphere_to_plane(vec3 w) {
    float s = 1.0f / sqrt(max(1.0f + w.z, 1e-12f));
    return vec2(w.x * s, w.y * s);
}
// Plane point with |p| ≤ √2 → unit local direction (|p| < 1: above the horizon).
RSL_SHARED vec3 plane_to_hemisphere(vec2 p) {
    float rho2 = min(dot(p, p), 2.0f);
    float s = sqrt(max(2.0f - rho2, 0.0f));  // √(1 + cosθ)
    return vec3(p.x * s, p.y * s, 1.0f - rho2);
}
// hemisphere_to_plane for table lookups: at (and numerically near) the
// antipode, whose image is the whole circle |p| = √2, the table's far corner.
RSL_SHARED vec2 lookup_plane_point(vec3 local) {
    if (local.z < -0.9999f) return vec2(1.5f, 1.5f);
    return hemisphere_to_plane(local);
}

// ---- lights as squares (src/render/square_lights.h) ----

// An RSL of half-diagonal r (solid angle 2r²) is the plane square of area r²:
// half-edge r / 2 (measure preserving; docs/METHOD.md "Rotatable square lights").
RSL_SHARED float square_half_edge_for_rsl(float half_diagonal) { return 0.5f * half_diagonal; }
// A square of solid angle Ω has plane area Ω / 2.
RSL_SHARED float half_edge_for_solid_angle(float solid_angle) { return 0.5f * sqrt(0.5f * solid_angle); }
// The cap a sphere of radius a subtends at distance d > a: 2π(1 − cos α),
// written 2π sin²α / (1 + cos α) against cancellation.
RSL_SHARED float sphere_cap_solid_angle(float radius, float distance) {
    float sin2 = min(1.0f, (radius / distance) * (radius / distance));
    return 2.0f * kPi * sin2 / (1.0f + sqrt(1.0f - sin2));
}
// A spot light's cone (glTF KHR_lights_punctual's smooth falloff): what
// reaches a point in unit direction w from the light (light → point) is
// scaled by clamp(dot(axis, w)·scale + offset, 0, 1)², with
// scale = 1 / max(1e-3, cos θ_inner − cos θ_outer), offset = −cos θ_outer · scale
// (spot_cone_scale_offset, src/core/sphere_light.h): 1 inside the inner
// cone, 0 outside the outer one. A point light is scale 0, offset 1.
RSL_SHARED float spot_cone_factor(vec3 axis, vec3 light_to_point, float scale, float offset) {
    float f = clamp(dot(axis, light_to_point) * scale + offset, 0.0f, 1.0f);
    return f * f;
}
// Whether a square of half-edge h centred on local direction w can overlap
// the upper hemisphere: |p(w)| = √(1 − w.z) < 1 + √2·h.
RSL_SHARED bool square_reaches_hemisphere(float local_z, float half_edge) {
    float reach = 1.0f + kSqrt2 * half_edge;
    return local_z > 1.0f - reach * reach;
}

// Isotropic tables are view-aligned: the local frame turned about the normal
// so that the view lies in the y–z plane. (cos φ_o, sin φ_o) of the local
// view wo; (1, 0) for a view along the normal.
RSL_SHARED vec2 view_alignment(vec3 wo) {
    float len2 = wo.x * wo.x + wo.y * wo.y;
    float inv = len2 > 1e-16f ? 1.0f / sqrt(len2) : 0.0f;
    return vec2(len2 > 1e-16f ? wo.y * inv : 1.0f, wo.x * inv);
}
// A plane point in the view-aligned frame, for alignment (cos φ_o, sin φ_o).
RSL_SHARED vec2 to_view_aligned(vec2 p, vec2 alignment) {
    return vec2(p.x * alignment.x - p.y * alignment.y, p.x * alignment.y + p.y * alignment.x);
}

// ---- visibility distance tables (fields/vdt.h) ----

// The VDT rule: visible fraction of a square of half-edge h whose centre has
// interpolated signed distance d.
RSL_SHARED float visible_fraction_from_distance(float d, float half_edge) {
    return clamp(0.5f + d / (2.0f * half_edge), 0.0f, 1.0f);
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

// ---- BRDF summed-area tables (src/brdf/brdf_table_lookup.cpp) ----

// The SAT corner pair bracketing coordinate x ∈ [0, n], and the upper one's weight.
struct CornerBracket {
    int lower;
    float upper_weight;
};
RSL_SHARED CornerBracket corner_bracket(float x, int n) {
    CornerBracket b;
    b.lower = min(int(x), n - 1);
    b.upper_weight = x - float(b.lower);
    return b;
}

// The 4×4 SAT corner taps of a square (centre c, half-edge h, plane units)
// on an n×n table: along x the corners bracketing the right edge (weights
// 1 − f, f) and the left edge (f − 1, −f); the same along y. The integral is
// Σ wx[m]·wy[l]·S(ax[m], by[l]) plus the mean offset × the clipped area.
struct SquareTaps {
    ivec4 ax;
    ivec4 by;
    vec4 wx;
    vec4 wy;
    float clipped_area;   // texel units: the square's area inside [0, n]²
    float inv_full_area;  // 1 / (the whole square's area in texel units)
};
// A square narrower than a table texel (a sun's) is read as one texel wide:
// the table holds texel averages, so nothing finer is there to read, and the
// corner sums' difference over a sliver of a texel is their float rounding,
// which the two renderers' different sums turn into different averages
// (2% on a glossy part under a glTF sun). kMinSquareTexels: the narrowest
// square's edge in table texels (half-edge kMinSquareTexels / n in plane
// units, where a texel is 2 / n wide).
RSL_CONST float kMinSquareTexels = 1.0f;
RSL_SHARED SquareTaps square_taps(vec2 c, float half_edge, int n) {
    float scale = 0.5f * float(n);  // plane → texel units
    float h = max(half_edge, kMinSquareTexels / float(n));
    float x0 = clamp((c.x - h + 1.0f) * scale, 0.0f, float(n));
    float x1 = clamp((c.x + h + 1.0f) * scale, 0.0f, float(n));
    float y0 = clamp((c.y - h + 1.0f) * scale, 0.0f, float(n));
    float y1 = clamp((c.y + h + 1.0f) * scale, 0.0f, float(n));
    CornerBracket a0 = corner_bracket(x0, n);
    CornerBracket a1 = corner_bracket(x1, n);
    CornerBracket b0 = corner_bracket(y0, n);
    CornerBracket b1 = corner_bracket(y1, n);
    SquareTaps t;
    t.ax = ivec4(a1.lower, a1.lower + 1, a0.lower, a0.lower + 1);
    t.wx = vec4(1.0f - a1.upper_weight, a1.upper_weight, a0.upper_weight - 1.0f, -a0.upper_weight);
    t.by = ivec4(b1.lower, b1.lower + 1, b0.lower, b0.lower + 1);
    t.wy = vec4(1.0f - b1.upper_weight, b1.upper_weight, b0.upper_weight - 1.0f, -b0.upper_weight);
    t.clipped_area = (x1 - x0) * (y1 - y0);
    float edge = 2.0f * h * scale;
    t.inv_full_area = 1.0f / (edge * edge);
    return t;
}

// Linear interpolation between v view samples at (k + ½)/v: t = u·v − ½,
// clamped to the first and last sample; the lower sample and the upper weight.
struct SampleLerp {
    int lower;
    float upper_weight;
};
RSL_SHARED SampleLerp sample_lerp(float t, int v) {
    float x = clamp(t, 0.0f, float(v - 1));
    SampleLerp s;
    s.lower = min(int(x), v - 2);
    s.upper_weight = x - float(s.lower);
    return s;
}
// Isotropic tables: the view's slice coordinate, linear in its plane radius √(1 − cos θ_o).
RSL_SHARED float isotropic_view_coordinate(float view_z, int v) {
    return sqrt(clamp(1.0f - view_z, 0.0f, 1.0f)) * float(v) - 0.5f;
}
// Anisotropic tables: a plane coordinate x ∈ [-1, 1] on the grid of v view
// samples (sample_lerp's t; samples at texel centres).
RSL_SHARED float view_grid_coordinate(float x, int v) { return (x + 1.0f) * 0.5f * float(v) - 0.5f; }
// Anisotropic tables: the view's plane point, clamped to the horizon (unit disk).
RSL_SHARED vec2 anisotropic_view_point(vec3 view) {
    vec2 p = hemisphere_to_plane(vec3(view.x, view.y, max(view.z, -0.999f)));
    float len2 = dot(p, p);
    if (len2 > 1.0f) p = p / sqrt(len2);
    return p;
}

// ---- the occluder field (fields/ovdf.h) ----

// The natural log of a positive normal float to 1.2e-7 (absolute where
// |log x| < 1, relative above; tests/fields/ovdf_test.cpp), the same
// arithmetic in both renderers and, unlike the libraries' log, in a loop the
// CPU vectorizes (its near-point locations, fields/ovdf_near.cpp). x = m·2^e
// with m in [√½, √2): log x = e·ln 2 + 2·atanh(s), s = (m − 1)/(m + 1), |s| ≤
// 0.172, whose series to s⁹ leaves 1e-9.
RSL_SHARED float portable_log(float x) {
    int bits = floatBitsToInt(x);
    int exponent = ((bits >> 23) & 255) - 127;
    float m = intBitsToFloat((bits & 8388607) | 1065353216);  // the mantissa in [1, 2)
    bool high = m > 1.41421356f;
    m = high ? 0.5f * m : m;
    exponent = high ? exponent + 1 : exponent;
    float s = (m - 1.0f) / (m + 1.0f);
    float s2 = s * s;
    float series = 0.222222222f;  // 2/9, 2/7, 2/5, 2/3, 2: 2·atanh(s)/s
    series = series * s2 + 0.285714286f;
    series = series * s2 + 0.4f;
    series = series * s2 + 0.666666667f;
    series = series * s2 + 2.0f;
    return float(exponent) * 0.693147181f + s * series;
}
// Continuous shell index of distance ratio d / R between the inner and the
// outer shell radii (× R): spacing 0 geometric, 1 linear, 2 inverse radius.
RSL_SHARED float ovdf_shell_coordinate(int spacing, int shells, float inner, float outer, float ratio) {
    float last = float(shells - 1);
    if (spacing == 0) return last * portable_log(max(ratio, 1e-6f) / inner) / portable_log(outer / inner);
    if (spacing == 1) return last * (ratio - inner) / (outer - inner);
    return last * (1.0f / max(ratio, 1e-6f) - 1.0f / inner) / (1.0f / outer - 1.0f / inner);
}
// The two shells around a shell coordinate (clamped inside): the lower one
// and the upper one's weight.
struct ShellPair {
    int lower;
    float upper_weight;
};
RSL_SHARED ShellPair ovdf_shell_pair(float coordinate, int shells) {
    float u = clamp(coordinate, 0.0f, float(shells - 1));
    ShellPair s;
    s.lower = min(int(u), shells - 2);
    s.upper_weight = u - float(s.lower);
    return s;
}

// The cube face whose normal is nearest to the unit direction (the first on
// ties), and the cosine to it.
struct CubeFace {
    int face;
    float cosine;
};
RSL_SHARED CubeFace cube_face(vec3 dir, const vec3 normals[6]) {
    CubeFace c;
    c.face = 0;
    c.cosine = -2.0f;
    for (int f = 0; f < kCubeFaces; ++f) {
        float d = dot(dir, normals[f]);
        if (d > c.cosine) {
            c.face = f;
            c.cosine = d;
        }
    }
    return c;
}
// The four sample taps (i, j) of an n×n face around unit direction dir and
// their bilinear weights: (i, j), (i+1, j), (i, j+1), (i+1, j+1). s, t: the
// face's axes; cosine: dir's cosine to the face normal.
struct SampleTaps {
    ivec4 i;
    ivec4 j;
    vec4 weight;
};
RSL_SHARED SampleTaps ovdf_sample_taps(vec3 dir, float cosine, vec3 s, vec3 t, int n) {
    float hi = float(n - 1);
    float inverse_cosine = 1.0f / cosine;
    float x = clamp((dot(dir, s) * inverse_cosine + 1.0f) * 0.5f * float(n) - 0.5f, 0.0f, hi);
    float y = clamp((dot(dir, t) * inverse_cosine + 1.0f) * 0.5f * float(n) - 0.5f, 0.0f, hi);
    int i0 = min(int(x), n - 2);
    int j0 = min(int(y), n - 2);
    float fx = x - float(i0);
    float fy = y - float(j0);
    SampleTaps taps;
    // Whole-vector arithmetic: the CPU builds and copies them in registers.
    taps.i = ivec4(i0) + ivec4(0, 1, 0, 1);
    taps.j = ivec4(j0) + ivec4(0, 0, 1, 1);
    taps.weight = vec4((1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy);
    return taps;
}
// Sample (shell, face, i, j) of faces of n×n samples, and its PCA segment
// (each face split m×m).
RSL_SHARED int ovdf_sample_index(int shell, int face, int i, int j, int n) {
    return ((shell * kCubeFaces + face) * n + j) * n + i;
}
RSL_SHARED int ovdf_segment_of(int shell, int face, int i, int j, int n, int m) {
    return ((shell * kCubeFaces + face) * m + j * m / n) * m + i * m / n;
}

// Plane radius of the bounding cone of a part of bounding radius R seen from
// distance d > R: √2·sin(½·asin x) = x / √(1 + √(1 − x²)), x = R/d — square
// roots only, which GLSL evaluates as C++ does (its asin is approximate).
RSL_SHARED float ovdf_cone_radius(float distance, float radius) {
    float x = min(radius / max(distance, 1e-30f), 1.0f);
    return x / sqrt(1.0f + sqrt(1.0f - x * x));
}
// A shell's zoomed table: table point = zoom × plane point, so that the
// bounding cone's edge maps to kOvdfZoomEdge (fields/ovdf.h). Inside the
// bounding sphere there is no cone: the part may lie in any direction, the
// ones away from its centre too (|p| up to √2, the antipode), so the table
// is zoomed out by 1/√2 to hold the whole sphere of directions in its
// inscribed disk. (At zoom 1 only the square's corners reached past |p| = 1,
// and every other direction away from the centre read the edge texel, the
// horizon: a chair in the middle of a room read the room's walls when it
// looked out of the room's open side.)
struct OvdfZoom {
    float zoom;
    float cone;  // plane radius of the bounding cone's edge
};
RSL_CONST float kOvdfInsideZoom = 0.70710678f;
RSL_SHARED OvdfZoom ovdf_zoom(float distance, float radius) {
    OvdfZoom z;
    z.zoom = kOvdfInsideZoom;
    z.cone = kOvdfNoCone;
    if (distance <= radius) return z;
    z.cone = ovdf_cone_radius(distance, radius);
    z.zoom = max(1.0f, kOvdfZoomEdge / z.cone);
    return z;
}
// A shell's distance in plane units from its table value (table units) at a
// plane point of radius `radial`: the part lies in the cone, D ≥ |p| − e.
RSL_SHARED float ovdf_plane_distance(float table_distance, OvdfZoom z, float radial) {
    return max(table_distance / z.zoom, radial - z.cone);
}
// The same with the table value already scaled by the shell's weight w > 0
// (w·D′), giving w × the shell's distance: the renderers' form.
RSL_SHARED float ovdf_weighted_plane_distance(float weighted_table_distance, float weight, OvdfZoom z, float radial) {
    return max(weighted_table_distance / z.zoom, weight * (radial - z.cone));
}
// The same bound with the cone seen from the receiver itself, after the
// shells' blend (exact, tighter than the nearer shell's).
RSL_SHARED float ovdf_receiver_distance(float blended, float radial, float cone) {
    return max(blended, radial - cone);
}
// The straight-edge rule (visible_fraction_from_distance) takes the shadow's
// edge for a line across the square: a square much larger than the part's
// silhouette near its edge loses half of itself to a part that covers a
// sliver of it. The part cannot shadow more of the square than its whole
// silhouette: `occluded_area`, the samples' blended shadowed area of their
// tables in plane units (Ovdf::occluded_area), bounds the shadowed share of
// the square of half-edge h. kOvdfNoAreaBound: no bound (a receiver inside
// the part stays dark).
RSL_CONST float kOvdfNoAreaBound = 3.0e38f;
RSL_SHARED float ovdf_area_bound(float visible, float occluded_area, float h) {
    return max(visible, 1.0f - occluded_area / (4.0f * h * h));
}
// A small occluder: the part's bounding cone seen from the receiver (plane
// radius `cone`) narrower than the light's square (cone < h). Its shadow is
// then a blob inside or across the square, and no straight edge describes
// it: where the blob sits across the square's edge the rule above shadows
// up to half the square, and the area bound all of the blob's area, while
// only the share of the blob inside the square is dark. The small-occluder
// rule takes the blob for a disk of its area A centred on the pole (the
// direction to the part's centre, the plane's origin) and the light for the
// square's inscribed disk, and shadows their overlap's share of the square.
// The inscribed disk, since every lookup (and the culling) takes a light
// whose square lies beyond the cone, |p| ≥ h + cone, for unshadowed
// (ovdf_unshadowed), and the blob (its radius clamped to the cone) must keep
// within that reach; a disk of the square's area reached 13% of h further,
// and culling changed the colours. Disks, since the square's turn about the
// pole is not known there (the pole frame's tangent follows the occluder's
// cube face, not the receiver's frame): a rule that turned with the frame
// changed at the faces' seams, and the GPU, whose face choice differs by
// rounding there, with it. It needs no table: the renderers skip the blend
// of PCA coefficients and rows, which in a yard of 128 parts was most of the
// other parts' shadows (86% of the lookups had cone < h). Against the truth it is as accurate as the tables, or slightly
// more (docs/RESULTS.md "Small occluders"); tests/fields/ovdf_test.cpp pins
// it against exact caps and a traced bar.
//
// The rule's weight: 1 for cone ≤ h, 0 (the tables alone) from cone ≥ 1.25 h,
// linear between, so that a part whose cone crosses a square's size as it
// moves does not pop, and the two renderers, whose cones differ by float
// rounding, do not take different rules at the edge.
RSL_CONST float kOvdfSmallOccluderRatio = 1.0f;  // the rule alone below cone = ratio × h
RSL_CONST float kOvdfSmallOccluderFade = 1.25f;  // the tables alone from cone = fade × h
RSL_SHARED float ovdf_small_occluder_weight(float cone, float h, float occluded_area) {
    // A field without areas has none to take (kOvdfNoAreaBound, or the GPU's
    // blend of it, which rounds below it); a real area is at most 8.
    if (!(occluded_area < 1.0e30f)) return 0.0f;
    return clamp((kOvdfSmallOccluderFade * h - cone) / ((kOvdfSmallOccluderFade - kOvdfSmallOccluderRatio) * h), 0.0f,
                 1.0f);
}
// The plane radius |p| of a light direction whose cosine to the pole is c:
// in the pole frame |p|² = 1 − c (the equal-area map), with no frame needed.
RSL_SHARED float ovdf_pole_radial(float cos_to_pole) { return sqrt(max(1.0f - cos_to_pole, 0.0f)); }
// arccos to 2e-8 rad (Abramowitz & Stegun 4.4.46), the same polynomial in
// both renderers: GLSL's acos is the driver's (llvmpipe's was 1e-4 off the
// C++ library's, so the two renderers' small-occluder shadows differed by
// that much), and libm's was 3% of a dense scene's shading.
RSL_SHARED float portable_acos(float x) {
    float a = min(abs(x), 1.0f);
    float p = -0.0012624911f;
    p = p * a + 0.0066700901f;
    p = p * a - 0.0170881256f;
    p = p * a + 0.0308918810f;
    p = p * a - 0.0501743046f;
    p = p * a + 0.0889789874f;
    p = p * a - 0.2145988016f;
    p = p * a + 1.5707963050f;
    float angle = sqrt(1.0f - a) * p;
    return x < 0.0f ? kPi - angle : angle;
}
// The area shared by two disks of radii a and b whose centres lie `distance` apart.
// Branch-free (the lens is computed always and selected), so that the CPU's
// loop over a block's small-occluder queries vectorizes; where the lens is
// not selected its divisions may give inf or NaN, which the selects drop.
RSL_SHARED float disk_overlap_area(float distance, float a, float b) {
    float smaller = min(a, b);
    float contained = kPi * smaller * smaller;
    float d2 = distance * distance;
    float alpha = portable_acos((d2 + a * a - b * b) / (2.0f * distance * a));
    float beta = portable_acos((d2 + b * b - a * a) / (2.0f * distance * b));
    float kite = (-distance + a + b) * (distance + a - b) * (distance - a + b) * (distance + a + b);
    float lens = min(a * a * alpha + b * b * beta - 0.5f * sqrt(max(kite, 0.0f)), contained);
    float overlap = distance <= abs(a - b) ? contained : lens;
    return distance >= a + b ? 0.0f : overlap;
}
// The visible share of the square of half-edge h whose centre lies at plane
// radius `radial` from the pole, that a small occluder of plane area A leaves.
// The blob's disk stays within the cone: A blends samples of two shells,
// and the nearer shell's, seen from closer, is the larger.
RSL_SHARED float ovdf_small_occluder_fraction(float radial, float occluded_area, float cone, float h) {
    float blob = min(sqrt(max(occluded_area, 0.0f) / kPi), cone);  // the disk of area A
    return 1.0f - disk_overlap_area(radial, h, blob) / (4.0f * h * h);
}
// The lookup's visible fraction from the tables' (straight edge, area bound)
// and the small-occluder rule's, by the rule's weight w.
RSL_SHARED float ovdf_fade_small_occluder(float tables, float small, float w) {
    return w <= 0.0f ? tables : w >= 1.0f ? small : w * small + (1.0f - w) * tables;
}
// A receiver within the OVDF part's bounding sphere is inside the part (a
// neighbour's vertex sunk into it at a joint, fully shadowed) where its
// samples' blended surface distance is below −kOvdfContactTolerance·R. A
// vertex on the surface counts as outside, as the ground truth counts a ray
// origin a few ray offsets inside another part (RayScene's
// origins_outside_surfaces); the blend near 0 is noise of a few mm either
// way, and below this tolerance it decided whether the sun glinted on the
// top of a shin standing in the thigh. Measured at the default frame
// (robot, sunsky, t = 0.5) against the truth: tolerance 0 / 0.001 R /
// 0.002 R / 0.005 R gave 13.7% / 7.1% / 7.8% / 10.4% over all vertices,
// objects 22.7% / 11.2% / 12.5% / 17.0% (larger tolerances light the hip
// balls sunk in the pelvis, which the truth leaves dark).
RSL_CONST float kOvdfContactTolerance = 0.001f;
// (Callers blend the surface distance only within the bounding sphere, d < R.)
RSL_SHARED bool ovdf_inside_part(float radius, float blended_surface_distance) {
    return blended_surface_distance < -kOvdfContactTolerance * radius;
}
// The radial spans (fields/ovdf_spans.h) decide that test first where they
// can. Along each radial line, coming in from outside the bounding sphere,
// the bake records where the line first enters the part (`enter`, a
// distance from the centre) and where it leaves that first solid span
// (`exit`). A receiver between the sphere and `enter` is outside; one within
// the span is inside; only one deeper than the span (a cup's cavity, a second
// span) is left to the surface distances. The lines lie on a cube map of
// n×n directions per face (axis-major: face 2a + (negative), the other two
// axes in order), bilinear between direction centres. Measured at the
// robot's own field settings, the blended surface distance had put the
// pelvis's surface 8 mm too far out at the hip crease and missed knees sunk
// into thighs (issue 17; docs/RESULTS.md, "Radial spans"). 256² lines per
// face, not 64²: against the truth whose ray offsets scale with each part,
// a seam vertex 0.1 mm inside a thigh is dark, and the blend between lines
// 7 mm apart (64², at the knee) could not tell it from one on the surface
// (robot, ennis t = 0: worst part shin_l 17% at 64² and 0.002 R, 10% at
// 256² and 0.001 R; docs/RESULTS.md, "Finer radial spans"). 3 MB per OVDF.
RSL_CONST int kOvdfSpanResolution = 256;
// How far (× R) a receiver must be beyond a span's ends to be decided: a
// vertex on a contact seam counts as outside, as in ovdf_inside_part (the
// truth counts origins a few ray offsets inside another part as outside).
// The spans are bilinear in the entry distance, which is convex along a flat
// face: at grazing lines the blend lies outside the face, so the margin must
// cover that too (at 64² lines and 0.001 R, 14% of the points 0.1 mm under a
// box's face read inside; tests/fields/ovdf_test.cpp). The margin is
// along the radial line, so at the knees, where the lines meet the thigh at
// cos 0.3, it is 3.3× the depth below the surface. Measured on the robot
// (scene settings, K = 30, field format 8; sun at t = 0, 0.5, 1 and ennis
// at t = 0, 0.5, 1) against the truth, whose exit margin lights a shin
// vertex 0.14 mm along its line inside the thigh (0.04 mm deep: the sun's
// glint at t = 0.5) and darkens one 0.22 mm inside (t = 0): 0.0004 R and
// below call the glint inside (shin_l 50%), 0.0005–0.0007 R are best at
// every frame, 0.0008 R and 0.001 R lose it (shin_l at t = 0 13% and
// 15.6%, against 11.3% at 0.0006 R); so the plateau's middle
// (docs/RESULTS.md, "The span margin, again").
RSL_CONST float kOvdfSpanTolerance = 0.0006f;
struct SpanTaps {
    ivec4 index;  // direction (face·n + j)·n + i
    vec4 weight;
};
// The four radial lines around offset v (point − centre, non-zero).
RSL_SHARED SpanTaps ovdf_span_taps(vec3 v, int n) {
    vec3 a = abs(v);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    int face = 2 * axis + (v[axis] < 0.0f ? 1 : 0);
    // The face's own table over [−1, 1]²: the other two axes over the major one.
    BilinearTaps t = bilinear_taps(n, vec2(v[(axis + 1) % 3], v[(axis + 2) % 3]) / a[axis]);
    SpanTaps taps;
    taps.index = t.index + ivec4(face * n * n);
    taps.weight = t.weight;
    return taps;
}
// A receiver at distance d from the centre against its blended span (enter,
// exit): 0 outside, 1 inside, −1 deeper than the span (undecided).
RSL_SHARED int ovdf_span_inside(float d, vec2 span, float radius) {
    float margin = kOvdfSpanTolerance * radius;
    if (d > span.x - margin) return 0;
    if (d > span.y + margin) return 1;
    return -1;
}
// The receiver's own bounding cone test: whether the lookup certainly gives 1
// for a light at cosine cos_to_center from the pole (|p|² = 1 − cos) and a
// square of half-edge h: the square lies beyond |p| − cone ≥ h. Branch-free,
// for the CPU's vectorized loops; the GPU runs it before each lookup.
RSL_SHARED bool ovdf_unshadowed(float cos_to_center, float cone, float half_edge) {
    float limit = half_edge + cone;
    return cos_to_center <= 1.0f - limit * limit;
}

// ---- the slab rule (src/render/square_lights.h) ----

// Half-angle of a cone around the light's direction holding the part of its
// square above any vertex's horizon, whatever the frame: the square's points
// lie within √2·h of its centre, along segments within plane radius ρ_max =
// min(√2, 1 + √2·h), and the inverse map stretches lengths by at most
// √2 / cos(θ_max / 2) (ρ = √2·sin(θ/2)).
RSL_SHARED float square_cone_half_angle(float half_edge) {
    float rho_max = min(kSqrt2, 1.0f + kSqrt2 * half_edge);
    float sin_half = rho_max / kSqrt2;
    float cos_half = sqrt(max(0.0f, 1.0f - sin_half * sin_half));
    if (cos_half < 1e-3f) return kPi;
    return min(kPi, 2.0f * half_edge / cos_half);
}
// sin β for the slab rule; 2 (never clears) once β reaches π/2.
RSL_SHARED float square_cone_sine(float half_edge) {
    float beta = square_cone_half_angle(half_edge);
    return beta >= 0.5f * kPi ? 2.0f : sin(beta);
}
// Which side of the slab [lo, hi] x lies on: 1 above, −1 below, 0 within.
RSL_SHARED float box_side(float x, float lo, float hi) { return x > hi ? 1.0f : (x < lo ? -1.0f : 0.0f); }
RSL_SHARED vec3 box_sides(vec3 lo, vec3 hi, vec3 p) {
    return vec3(box_side(p.x, lo.x, hi.x), box_side(p.y, lo.y, hi.y), box_side(p.z, lo.z, hi.z));
}
// The slab rule: a receiver beyond a face of the occluder's bounding box
// (sides, in the part's frame) is unshadowed by it from a square whose
// directions all leave that face's plane outwards: some s_a·L_a ≥ sin β(h).
RSL_SHARED bool clears_box_face(vec3 sides, vec3 light, float sin_beta) {
    return max(sides.x * light.x, max(sides.y * light.y, sides.z * light.z)) >= sin_beta;
}
// The world form: light = inverse_linear·(world direction), not normalized,
// and face_scale = the lengths of inverse_linear's rows (the faces' world
// normals), so that the test holds for scaled parts too.
RSL_SHARED bool clears_box_face_scaled(vec3 sides, vec3 inverse_linear_light, vec3 face_scale, float sin_beta) {
    return clears_box_face(sides, inverse_linear_light / face_scale, sin_beta);
}

// ---- shadow maps (the GL renderer's shadow-mapped baseline, src/gl/shadow_maps.h) ----
//
// Not part of the RSL sum: a competitor's visibility factor for environment
// lights (RenderOptions::shadow_maps, docs/GPU.md "Shadow-mapped visibility").
// One orthographic depth map per light along its centre direction L, over a
// sphere that holds the posed scene; the filter's taps are the light
// square's own directions (the grid of exact_visibility.h), each moved across
// the map by how far it travels towards the light.

// The filter's taps: a Fibonacci lattice of kShadowTaps points over the
// square (point i at ((i + ½)/n, ((i·step mod n) + ½)/n) of the unit
// square): no two taps share a row or a column, so a straight shadow edge
// crossing the square moves the lit fraction in steps of about 1/n, where
// a 5×5 grid steps by 1/5 when the edge runs along its rows.
RSL_CONST int kShadowTaps = 21;
RSL_CONST int kShadowLatticeStep = 13;
// Bias, in texels (1 / resolution: the same length across and in depth,
// see shadow_map_point). Each texel a tap reads is compared with the
// receiver's own tangent plane at the texel's centre (the receiver-plane
// depth bias: a large kernel on a plane tilted to the light would otherwise
// shadow the plane itself), less this constant for the depth's
// interpolation and the facets around the vertex. The receiver is not moved
// off its surface along its normal: that moved shadow edges by the offset ×
// tan θ (1.5 texels doubled tests/gl/shadow_map_test.cpp's error at 30°).
RSL_CONST float kShadowDepthBiasTexels = 1.0f;
// Least cosine to L used in a tap's slope and the receiver plane's gradient,
// so that grazing directions and planes stay finite.
RSL_CONST float kShadowMinCosine = 0.2f;

// The map's axes for the unit light direction L (towards the light): x =
// any_orthonormal(L), y = L × x, z = L.
RSL_SHARED LocalFrame shadow_map_frame(vec3 light) {
    LocalFrame m;
    m.z = light;
    m.x = any_orthonormal(light);
    m.y = cross(light, m.x);
    return m;
}
// A world point in the map of the sphere (centre, radius) along axes m: (u, v)
// ∈ [0, 1]² across, depth ∈ [0, 1] from the sphere's point nearest the light.
// All three scale by 0.5 / radius, so a map offset and a depth difference
// are the same length (a texel is 1 / resolution in both).
RSL_SHARED vec3 shadow_map_point(LocalFrame m, vec3 center, float radius, vec3 world) {
    vec3 d = frame_to_local(m, world - center);
    float s = 0.5f / radius;
    return vec3(0.5f + s * d.x, 0.5f + s * d.y, 0.5f - s * d.z);
}
// The map offset per unit of depth travelled towards the light along world
// direction w: a ray leaving the receiver along w reaches depth d − Δ at map
// offset Δ × slope.
RSL_SHARED vec2 shadow_map_slope(LocalFrame m, vec3 w) {
    vec3 d = frame_to_local(m, w);
    return vec2(d.x, d.y) / max(d.z, kShadowMinCosine);
}
// The receiver's tangent plane (world normal n) in the map: its depth
// change per unit map offset.
RSL_SHARED vec2 shadow_receiver_gradient(LocalFrame m, vec3 n) {
    vec3 d = frame_to_local(m, n);
    return vec2(d.x, d.y) / max(d.z, kShadowMinCosine);
}
// Tap i of the lattice over the plane square (centre c, half-edge h).
RSL_SHARED vec2 shadow_tap_point(vec2 c, float half_edge, int i) {
    float n = float(kShadowTaps);
    float u = (float(i) + 0.5f) / n;
    float v = (float((i * kShadowLatticeStep) % kShadowTaps) + 0.5f) / n;
    return c + half_edge * vec2(2.0f * u - 1.0f, 2.0f * v - 1.0f);
}

// ---- occluders of exact shape: flat rectangles and boxes (src/render/occluder_shape.h) ----
//
// A ground or a wall is one flat rectangle, and its shadow is known exactly:
// a ray leaves the receiver and crosses the rectangle's plane or not. Its
// OVDF, sampled on shells, blends samples from both sides of the plane and
// comes out far too dark near it (docs/RENDERER.md, "Occluders of exact shape").
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
    vec3 w = plane_to_hemisphere(tap);
    return frame.x * w.x + frame.y * w.y + frame.z * w.z;
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

// RSL_GLSL_END (the GPU's copy ends here)

}  // namespace rsl::shading
