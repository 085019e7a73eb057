#pragma once
// Smooth closed primitives for the generated assets, tessellated with analytic
// normals (the surface's own normal, not one averaged from triangles) and
// tangents. Every builder returns a closed, edge-manifold mesh whose triangles
// wind counter-clockwise seen from outside, except grid_plane (an open sheet).
//
// Surfaces of revolution are described by a 2D profile in the (r, y) half
// plane, r ≥ 0 the distance from the Y axis. A profile is a G1 chain of lines
// and circular arcs, so every sample has an exact normal.
#include <vector>

#include "src/core/math.h"
#include "src/core/mesh.h"

namespace rsl::assets {

// One sample of a profile: position and outward unit normal in the (r, y) plane.
struct ProfileSample {
    Vec2 point;   // (r, y)
    Vec2 normal;  // (n_r, n_y)
};

// A chain of lines and circular arcs traversed so that the solid lies on the
// left: the outward normal is the tangent turned clockwise. A profile that
// starts and ends on the axis (r = 0) closes into a sphere-like surface; a
// closed loop (end == start) revolves into a torus-like one.
class Profile {
public:
    explicit Profile(Vec2 start) : cursor_(start), start_(start) {}

    Profile& line_to(Vec2 end);
    // Arc around `center` from the current point, sweeping `radians`
    // (positive = counter-clockwise in the (r, y) plane).
    Profile& arc(Vec2 center, float radians);
    // Polyline through `points` with every interior corner rounded by an arc of
    // (at most) `fillet_radius`, so the chain stays G1. The first point is
    // reached by a line from the current point; the last point is reached by a
    // straight line, without a fillet.
    Profile& rounded_polyline(const std::vector<Vec2>& points, float fillet_radius);

    Vec2 cursor() const { return cursor_; }
    float length() const;
    // Samples by arc length, about `spacing` apart (arcs at least every 12°);
    // segment joints are shared samples.
    std::vector<ProfileSample> sample(float spacing) const;

private:
    struct Segment {
        bool is_arc = false;
        Vec2 a, b;          // line: endpoints
        Vec2 center;        // arc
        float radius = 0, angle0 = 0, sweep = 0;
        float length() const;
        ProfileSample at(float fraction) const;
    };
    std::vector<Segment> segments_;
    Vec2 cursor_, start_;
};

// Revolves a profile about +Y with `segments` vertices per ring. Samples on the
// axis become single pole vertices; a profile whose last sample equals its
// first (to 1e-6) is treated as periodic (torus).
TriangleMesh revolve(const std::vector<ProfileSample>& profile, int segments);
// Segment count that keeps ring vertices about `spacing` apart at the largest radius.
int segments_for(const std::vector<ProfileSample>& profile, float spacing, int minimum = 12);

// Solids centered at the origin, axis +Y where one applies.
TriangleMesh sphere(float radius, float spacing);
TriangleMesh capsule(float radius, float half_length, float spacing);
// Two spheres (radius r_bottom at y = 0, r_top at y = length) joined by their
// common tangent cone: a tapered limb.
TriangleMesh round_cone(float r_bottom, float r_top, float length, float spacing);
// A box of the given half extents whose edges and corners are rounded with
// `radius` (≤ the smallest half extent); vertices about `spacing` apart.
TriangleMesh rounded_box(Vec3 half_extents, float radius, float spacing);
// Ring of major radius `major` (in the XZ plane) and tube radius `minor`.
TriangleMesh torus(float major, float minor, float spacing);
// Open square sheet at y = 0, normal +Y, (cells_x + 1) × (cells_z + 1) vertices.
TriangleMesh grid_plane(float size_x, float size_z, int cells_x, int cells_z);

// Applies an affine transform: positions by m, normals by its inverse
// transpose, tangents by m (re-orthogonalized against the normal).
void transform_mesh(TriangleMesh& mesh, const Mat4& m);
// Appends src's vertices and triangles to dst (a part made of several solids),
// with their texture coordinates when every vertex so far has them.
void append_mesh(TriangleMesh& dst, const TriangleMesh& src);
// Sets tangents from the normals: the part's +X axis projected into each
// tangent plane (+Z where the normal is nearly ±X), handedness +1.
void set_axis_tangents(TriangleMesh& mesh);

// Convenience for placing a solid inside a part.
Mat4 translate_rotate(Vec3 translation, Vec3 axis = Vec3(0, 1, 0), float radians = 0);

}  // namespace rsl::assets
