#pragma once
// The OVDF's radial spans: the receiver's inside test (shading_core.h
// ovdf_span_inside). Along each radial line from the part's bounding-sphere
// centre (kOvdfSpanResolution² directions per cube face), coming in from
// outside the sphere, where the line first enters the part and where it
// leaves that first solid span. The blended surface distances of the shell
// samples, 0.1 m apart on a robot, placed a surface by their linear blend
// and missed by millimetres where two parts meet; a ray along the line does
// not.
#include <vector>

#include "src/fields/solid_pieces.h"
#include "src/shading/ovdf_inside.h"

namespace rsl {

// The unit direction of radial line (face, i, j) of the n×n-per-face cube
// map that shading::ovdf_span_taps reads.
Vec3 ovdf_span_direction(int face, int i, int j, int n);

// (enter, exit) per radial line, interleaved, distances from `center`:
// depth is counted over the whole mesh, so that overlapping closed pieces (a
// waist sunk into a pelvis) make one span. Faces met from behind before any
// entry (a room's walls, turned inwards) enclose nothing and are passed. A
// line that enters and never leaves before the centre ends its span at 0
// when the centre is inside the part; otherwise the mesh is open there (a
// bowl of one sheet) and the span is empty (exit = enter), leaving what lies
// beyond to the surface distances. A line that meets nothing has (0, 0).
std::vector<float> bake_radial_spans(const SolidPieces& pieces, const Vec3& center, float radius, int n);

}  // namespace rsl
