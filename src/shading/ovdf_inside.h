#pragma once
// Whether a receiver lies inside an occluder's part (a joint's sunk
// vertex): the radial spans first, then the blended surface distance
// (src/fields/ovdf_spans.h, docs/design/FIELDS.md).
#include "src/shading/interpolation.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// A receiver within the OVDF part's bounding sphere is inside the part (a
// neighbour's vertex sunk into it at a joint, fully shadowed) where its
// samples' blended surface distance is below −kOvdfContactTolerance·R. A
// vertex on the surface counts as outside, as the ground truth counts a ray
// origin a few ray offsets inside another part (RayScene's
// origins_outside_surfaces): the blend near 0 is noise of a few mm either
// way. The value is the best of a sweep against the truth
// (docs/journal/parameter-sweeps.md).
RSL_CONST float kOvdfContactTolerance = 0.001f;
// (Callers blend the surface distance only within the bounding sphere, d < R.)
RSL_SHARED bool ovdf_inside_part(float radius, float blended_surface_distance) {
    return blended_surface_distance < -kOvdfContactTolerance * radius;
}
// The radial spans (src/fields/ovdf_spans.h) decide that test first where they
// can. Along each radial line, coming in from outside the bounding sphere,
// the bake records where the line first enters the part (`enter`, a
// distance from the centre) and where it leaves that first solid span
// (`exit`). A receiver between the sphere and `enter` is outside; one within
// the span is inside; only one deeper than the span (a cup's cavity, a second
// span) is left to the surface distances, which put surfaces millimetres off
// at creases. The lines lie on a cube map of n×n directions per face
// (axis-major: face 2a + (negative), the other two axes in order), bilinear
// between direction centres; 256² per face (3 MB per OVDF) tell a seam
// vertex 0.1 mm inside a part from one on its surface
// (docs/journal/parameter-sweeps.md).
RSL_CONST int kOvdfSpanResolution = 256;
// How far (× R) a receiver must be beyond a span's ends to be decided: a
// vertex on a contact seam counts as outside, as in ovdf_inside_part (the
// truth counts origins a few ray offsets inside another part as outside).
// The spans are bilinear in the entry distance, which is convex along a flat
// face: at grazing lines the blend lies outside the face, so the margin must
// cover that too (tests/fields/ovdf_test.cpp). The margin is along the
// radial line, so where lines meet a surface obliquely it is several times
// the depth below it. The value is the middle of the plateau a sweep against
// the truth found (docs/journal/parameter-sweeps.md).
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

// RSL_GLSL_END

}  // namespace rsl::shading
