// The cases of tests/gl/shading_core_test.cpp, in the shading core's common
// subset of C++ and GLSL (src/shading/shading_core.h), so that both sides
// map the same random inputs to the same arguments: C++ includes this file,
// and the test reads the text between the markers into its fragment shader.
// Each mode calls a group of shared functions and packs their results
// (integers as floats, exact here) into two vec4.
#pragma once
#include "src/shading/shading_core.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

RSL_CONST int kShadingCoreModes = 19;

struct CaseOutput {
    vec4 first;
    vec4 second;
};

// a, b: uniform in [-1, 1]⁴; normals, s, t: the OVDF cube faces' axes.
RSL_SHARED CaseOutput shading_core_case(int mode, vec4 a, vec4 b, const vec3 normals[6], const vec3 s[6],
                                        const vec3 t[6]) {
    CaseOutput o;
    o.first = vec4(0.0f);
    o.second = vec4(0.0f);
    vec3 w = normalize(vec3(a.x, a.y, a.z) + vec3(0.0f, 0.0f, 1e-3f));
    float ha = 0.002f + 0.6f * abs(a.w);  // a half-edge
    int n = 2 + int(30.0f * abs(b.z));     // a table resolution
    if (mode == 0) {  // the equal-area map
        vec2 p = hemisphere_to_plane(w);
        vec3 near_antipode = normalize(vec3(0.005f * a.x, 0.005f * a.y, -1.0f));  // z < -0.9999
        vec2 q = lookup_plane_point(b.w > 0.0f ? w : near_antipode);
        vec3 back = plane_to_hemisphere(vec2(1.45f * b.x, 1.45f * b.y));
        o.first = vec4(p.x, p.y, q.x, q.y);
        o.second = vec4(back.x, back.y, back.z, square_half_edge_for_rsl(abs(b.z)));
    } else if (mode == 1) {  // frames (a missing tangent half of the time: any_orthonormal)
        vec3 tangent = b.w > 0.5f ? vec3(0.0f) : vec3(b.x, b.y, b.z);
        LocalFrame f = frame_from_normal_tangent(w, tangent);
        vec3 local = frame_to_local(f, vec3(a.w, b.w, 0.5f));
        o.first = vec4(f.x.x, f.x.y, f.x.z, f.y.x);
        o.second = vec4(f.y.y, f.y.z, local.x, local.y);
    } else if (mode == 2) {  // lights as squares, the VDT rule, view alignment
        float radius = 0.01f + abs(a.x);
        float solid_angle = sphere_cap_solid_angle(radius, radius * (1.0001f + 10.0f * abs(a.y)));
        vec2 alignment = view_alignment(w);
        o.first = vec4(solid_angle, half_edge_for_solid_angle(solid_angle),
                       square_reaches_hemisphere(a.z, ha) ? 1.0f : 0.0f, visible_fraction_from_distance(b.x, ha));
        o.second = vec4(square_cone_half_angle(abs(b.y)), square_cone_sine(abs(b.y)), alignment.x, alignment.y);
    } else if (mode == 3) {  // bilinear taps
        BilinearTaps taps = bilinear_taps(n, vec2(1.6f * a.x, 1.6f * a.y));
        o.first = vec4(taps.index);
        o.second = taps.weight;
    } else if (mode == 4 || mode == 5) {  // BRDF SAT square taps
        SquareTaps taps = square_taps(vec2(1.5f * a.x, 1.5f * a.y), ha, n);
        if (mode == 4) {
            o.first = vec4(taps.ax) + 1000.0f * vec4(taps.by);
            o.second = taps.wx;
        } else {
            o.first = taps.wy;
            o.second = vec4(taps.clipped_area, taps.inv_full_area, taps.offset_area, float(taps.texels));
        }
    } else if (mode == 6) {  // view samples
        int v = 2 + int(8.0f * abs(b.z));
        LerpPair lerp = sample_lerp(10.0f * a.x, v);
        vec2 view = anisotropic_view_point(normalize(vec3(b.x, b.y, b.w)));
        vec2 aligned = to_view_aligned(vec2(a.y, a.z), view_alignment(w));
        o.first = vec4(float(lerp.lower), lerp.upper_weight, isotropic_view_coordinate(a.y, v), view_grid_coordinate(a.z, v));
        o.second = vec4(view.x, view.y, aligned.x, aligned.y);
    } else if (mode == 7) {  // shells, zoom and cone
        int spacing = min(2, int(3.0f * abs(b.w)));
        int shells = 2 + int(20.0f * abs(b.z));
        float coordinate = ovdf_shell_coordinate(spacing, shells, 0.3f + 0.2f * abs(b.x), 4.0f + 20.0f * abs(b.y),
                                                 0.1f + 30.0f * abs(a.x));
        LerpPair pair = ovdf_shell_pair(coordinate, shells);
        float radius = 0.1f + abs(a.y);
        float distance = radius * (0.5f + 10.0f * abs(a.z));
        OvdfZoom zoom = ovdf_zoom(distance, radius);
        float radial = 1.4f * abs(b.x);
        o.first = vec4(coordinate, float(pair.lower), pair.upper_weight, ovdf_cone_radius(distance, radius));
        o.second = vec4(zoom.zoom, zoom.cone < kOvdfNoCone ? zoom.cone : -1.0f, ovdf_plane_distance(a.w, zoom, radial),
                        ovdf_weighted_plane_distance(a.w, 0.1f + abs(b.y), zoom, radial));
    } else if (mode == 8 || mode == 9) {  // cube faces and sample taps
        CubeFace face = cube_face(w, normals);
        int m = 1 + int(2.0f * abs(b.x));
        SampleTaps taps = ovdf_sample_taps(w, face.cosine, s[face.face], t[face.face], n * m);
        if (mode == 8) {
            o.first = vec4(float(face.face), face.cosine,
                           float(ovdf_sample_index(int(5.0f * abs(b.y)), face.face, taps.i[0], taps.j[3], n * m)),
                           float(ovdf_segment_of(int(5.0f * abs(b.y)), face.face, taps.i[3], taps.j[0], n * m, m)));
            o.second = taps.weight;
        } else {
            o.first = vec4(taps.i);
            o.second = vec4(taps.j);
        }
    } else if (mode == 10) {  // the receiver's cone, the slab rule and a spot light's cone
        float spot_scale = 1.0f / (0.02f + abs(b.w));
        float spot = spot_cone_factor(w, normalize(vec3(b.x, b.y, b.z) + vec3(1e-3f)), spot_scale, -a.w * spot_scale);
        vec3 lo = vec3(-0.5f, -0.3f, -0.2f);
        vec3 hi = vec3(0.4f, 0.6f, 0.1f);
        vec3 sides = box_sides(lo, hi, vec3(a.x, a.y, a.z));
        vec3 scale = vec3(0.5f + abs(b.x), 0.5f + abs(b.y), 0.5f + abs(b.z));
        float sine = square_cone_sine(0.5f * ha);
        o.first = vec4(ovdf_unshadowed(a.w, abs(b.x), ha) ? 1.0f : 0.0f, ovdf_receiver_distance(a.w, abs(b.y), abs(b.z)),
                       box_side(a.x, lo.x, hi.x), sides.x + 10.0f * sides.y + 100.0f * sides.z);
        o.second = vec4(clears_box_face(sides, w, sine) ? 1.0f : 0.0f,
                        clears_box_face_scaled(sides, w * scale, scale, sine) ? 1.0f : 0.0f, sine, spot);
    } else if (mode == 12) {  // exact shapes: a rectangle's and a box's rays, then a square's visible share
        vec3 point = vec3(2.0f * a.x, 2.0f * a.y, 0.5f * a.z);
        vec3 hi = vec3(0.5f + abs(b.x), 0.5f + abs(b.y), 0.2f + 0.5f * abs(a.w));
        vec3 flat_hi = vec3(hi.x, hi.y, 0.0f);
        LocalFrame f = frame_from_normal_tangent(normalize(vec3(b.z, b.w, a.w) + vec3(0.0f, 0.0f, 1e-3f)), vec3(1.0f, 0.0f, 0.0f));
        vec2 c = vec2(0.8f * b.x, 0.8f * b.w);
        vec3 outside = point + vec3(0.0f, 0.0f, hi.z + 0.1f);  // above the box
        o.first = vec4(planar_blocks(point, w, vec2(hi.x, hi.y)) ? 1.0f : 0.0f, box_blocks(outside, -w, -hi, hi) ? 1.0f : 0.0f,
                       shape_visible_fraction(kShapeRectangle, point, f, c, ha, -flat_hi, flat_hi),
                       shape_visible_fraction(kShapeBox, outside, f, c, ha, -hi, hi));
        o.second = vec4(shape_visible_fraction(kShapeRectangle, vec3(point.x, point.y, 0.0f), f, c, ha, -flat_hi, flat_hi),
                        shape_visible_fraction(kShapeBox, vec3(point.x, point.y, hi.z), f, c, ha, -hi, hi), 0.0f, 0.0f);
    } else if (mode == 11) {  // the shadow-mapped baseline: map frame and point, a tap's slope, the receiver's gradient, the taps
        LocalFrame m = shadow_map_frame(w);
        vec3 q = shadow_map_point(m, vec3(b.x, b.y, b.z), 0.5f + abs(a.w), 2.0f * vec3(a.x, a.y, a.z));
        vec2 slope = shadow_map_slope(m, normalize(vec3(b.x, b.y, b.w) + vec3(1e-3f)));
        vec2 gradient = shadow_receiver_gradient(m, normalize(vec3(a.y, b.w, a.x) + vec3(1e-3f)));
        vec2 tap = shadow_tap_point(vec2(a.x, a.y), ha, min(kShadowTaps - 1, int(float(kShadowTaps) * abs(b.z))));
        o.first = vec4(q.x, q.y, q.z, tap.x);
        o.second = vec4(slope.x, slope.y, gradient.y, tap.y);
    } else if (mode == 13) {  // the radial spans: a point's four lines and the inside decision
        vec3 v = 3.0f * vec3(a.x, a.y, a.z) + vec3(0.0f, 0.0f, 1e-3f);
        SpanTaps taps = ovdf_span_taps(v, n);
        vec2 span = vec2(0.5f + abs(b.x), 0.5f * abs(b.y));
        o.first = vec4(taps.index);
        o.second = vec4(taps.weight.x, taps.weight.w,
                        float(ovdf_span_inside(length(v) / 3.0f, span, 1.0f + abs(b.w))),
                        float(ovdf_span_inside(span.x - 0.002f * abs(a.w), span, 1.0f)));
    } else if (mode == 14) {  // the small-occluder rule, and a light's radius from the pole
        // Squares of half-edge ≥ 0.05: the rule divides the disks' overlap by
        // the square's area 4h², which for the smallest squares above
        // magnifies the overlap's float rounding (1e-7 of the disks') past
        // the comparison's tolerance, on either side alike.
        ha = 0.05f + 0.5f * abs(a.w);
        float cone = 0.01f + 0.5f * abs(b.x);
        float area = 0.3f * abs(b.y);  // at times more than the cone's disk holds
        float radial = 1.4f * abs(b.w);
        vec3 pole = normalize(vec3(b.x, b.y, b.z) + vec3(0.0f, 0.0f, 1e-3f));
        o.first = vec4(ovdf_small_occluder_weight(cone, ha, area), disk_overlap_area(radial, ha, 0.5f * abs(b.z)),
                       ovdf_small_occluder_fraction(radial, area, cone, ha), ovdf_fade_small_occluder(a.x, a.y, b.z));
        o.second = vec4(ovdf_pole_radial(dot(w, pole)), ovdf_small_occluder_weight(cone, ha, 2.0e30f),
                        ovdf_small_occluder_fraction(ovdf_pole_radial(dot(w, pole)), area, cone, ha), portable_acos(a.z));
    } else if (mode == 15) {  // the ray baseline's seeds, a jittered sample and its grid point
        uvec2 seed = ray_seed(int(4096.0f * abs(a.x)), int(1.0e6f * abs(a.y)), int(128.0f * abs(a.z)));
        vec2 in_cell = jitter_in_cell(seed, int(256.0f * abs(b.x)));
        vec2 p = square_grid_point(vec2(a.w, b.y), ha, 1 + int(7.0f * abs(b.z)), int(3.0f * abs(b.w)), 1, in_cell);
        o.first = vec4(float(seed.x & 0xffffu), float(seed.x >> 16), float(seed.y & 0xffffu), float(seed.y >> 16));
        o.second = vec4(in_cell.x, in_cell.y, p.x, p.y);
    } else if (mode == 16) {  // the exact diffuse light: a square's mean cosine (across the horizon too), the gain, cube taps
        vec2 c = 1.3f * vec2(a.x, a.y);
        CubeNodeTaps taps = cube_node_taps(w, n);
        o.first = vec4(square_average_cosine(c, 0.5f * ha), square_average_cosine(0.3f * c, 0.2f * ha),
                       diffuse_light_gain(abs(b.x), abs(b.y), abs(b.w) - 0.1f), float(taps.first));
        o.second = vec4(float(taps.row), taps.weight.x, taps.weight.y, diffuse_light_gain(abs(b.x), abs(b.y), 0.5f + abs(b.w)));
    } else if (mode == 17) {  // a sphere light's square at a point: outside the sphere, and inside it a tenth of the time
        vec3 x = 3.0f * vec3(a.x, a.y, a.z);
        vec3 center = 3.0f * vec3(b.x, b.y, b.z);
        float radius = 0.01f + 2.0f * abs(a.w);
        if (b.w > 0.8f) radius = length(center - x) + 0.01f;
        SphereSquare square = sphere_square(x, center, radius);
        o.first = vec4(square.direction.x, square.direction.y, square.direction.z, square.lit ? 1.0f : 0.0f);
        o.second = vec4(square.solid_angle, square.half_edge, 0.0f, 0.0f);
    } else if (mode == 18) {  // a block's bounding sphere over five points
        vec3 p0 = vec3(a.x, a.y, a.z);
        vec3 p1 = vec3(b.x, b.y, b.z);
        vec3 p2 = vec3(a.w, b.w, a.x * b.y);
        vec3 p3 = 0.5f * vec3(b.w, a.z, a.y);
        vec3 p4 = 10.0f * vec3(a.x * a.y, b.z * b.w, a.w * b.x);
        PointBox box = point_box(p0);
        box = point_box_add(box, p1);
        box = point_box_add(box, p2);
        box = point_box_add(box, p3);
        box = point_box_add(box, p4);
        vec3 center = point_box_center(box);
        float r2 = farther_squared(0.0f, center, p0);
        r2 = farther_squared(r2, center, p1);
        r2 = farther_squared(r2, center, p2);
        r2 = farther_squared(r2, center, p3);
        r2 = farther_squared(r2, center, p4);
        o.first = vec4(center.x, center.y, center.z, bounding_radius(r2));
        o.second = vec4(box.lo.x, box.hi.y, box.lo.z, r2);
    }
    return o;
}

// RSL_GLSL_END

}  // namespace rsl::shading
