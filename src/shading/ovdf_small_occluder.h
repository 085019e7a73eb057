#pragma once
// The occluder field's small-occluder rule (docs/design/FIELDS.md "Small
// occluders"): a part whose bounding cone is narrower than the light's
// square shadows the overlap of two disks, with no table.
#include "src/shading/ovdf_tables.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

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
// more (docs/journal/results-history.md "Small occluders"); tests/fields/ovdf_test.cpp pins
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

// RSL_GLSL_END

}  // namespace rsl::shading
