#pragma once
// The visibility distance table's rule (RSL paper §4.2; src/fields/visibility_distance_table.h): the
// visible share of a square from the signed distance at its centre.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

// Value of a visibility distance table whose map has no boundary (all
// visible or all blocked), plane units: more than any square's half-edge.
RSL_CONST float kVdtNoBoundaryDistance = 4.0f;

// The VDT rule: visible fraction of a square of half-edge h whose centre has
// interpolated signed distance d.
RSL_SHARED float visible_fraction_from_distance(float d, float half_edge) {
    return clamp(0.5f + d / (2.0f * half_edge), 0.0f, 1.0f);
}

// RSL_GLSL_END

}  // namespace rsl::shading
