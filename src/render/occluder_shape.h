#pragma once
// Parts of exact shape — a flat rectangle (a ground, a wall, a table top
// modelled as one quad grid) or a box (a crate, a step, a building block) —
// cast their shadows exactly: both renderers test the light square's filter
// taps against the shape (shading::shape_visible_fraction) in place of the
// part's OVDF. Near such a part the OVDF blends samples from both sides of a
// face: a box resting on the ground came out 15–30% too dark on its sides,
// and the box under another 9% off (docs/design/RENDERER.md, "Occluders of exact
// shape").
#include <optional>

#include "src/core/mesh.h"
#include "src/shading/shapes.h"

namespace rsl {

// The shape in its own coordinates: the mesh frame moved to `center` and
// turned to the axes (s, t, normal); there it is [lo, hi] (a rectangle has
// lo.z = hi.z = 0 and lies across s and t).
struct OccluderShape {
    int kind = shading::kShapeNone;
    Vec3 center{0}, s{1, 0, 0}, t{0, 1, 0}, normal{0, 0, 1};
    Vec3 lo{0}, hi{0};

    Vec3 to_shape(const Vec3& p) const { return direction_to_shape(p - center); }
    Vec3 direction_to_shape(const Vec3& d) const { return Vec3(glm::dot(d, s), glm::dot(d, t), glm::dot(d, normal)); }
};

// The rectangle a mesh covers exactly, if it is one: every vertex within
// 10⁻⁵ of its size of one plane, and its triangles' area that of the
// rectangle its vertices span along one of the largest triangle's edges and
// the normal's cross (within 0.1%, so no hole, disc or L-shape passes).
std::optional<OccluderShape> find_rectangle(const TriangleMesh& mesh);
// The box a mesh covers exactly, if it is one, axis-aligned in the mesh's
// frame: every triangle on one face of its bounding box, and their area the
// box's surface (within 0.1%).
std::optional<OccluderShape> find_box(const TriangleMesh& mesh);
// A rectangle, else a box, else kShapeNone.
OccluderShape find_occluder_shape(const TriangleMesh& mesh);

}  // namespace rsl
