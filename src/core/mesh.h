#pragma once
// Triangle meshes: the geometry of one rigid part, in the part's own frame.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/math.h"

namespace rsl {

struct Bounds {
    Vec3 lo{1e30f}, hi{-1e30f};
    void extend(const Vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    Vec3 center() const { return 0.5f * (lo + hi); }
    bool empty() const { return lo.x > hi.x; }
};

struct BoundingSphere {
    Vec3 center{0};
    float radius = 0;
};

struct TriangleMesh {
    std::string name;
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;    // per vertex, unit
    std::vector<Vec4> tangents;   // per vertex: xyz unit tangent ⟂ normal, w = handedness ±1
    std::vector<Vec2> texcoords;  // per vertex (glTF TEXCOORD_0: (0, 0) the image's top-left), or empty
    std::vector<uint32_t> indices;  // 3 per triangle
    size_t degenerate_dropped = 0;  // degenerate triangles validate_and_complete removed when loading

    size_t vertex_count() const { return positions.size(); }
    size_t triangle_count() const { return indices.size() / 3; }

    Bounds bounds() const;
    BoundingSphere bounding_sphere() const;  // centered on the bounds' center
    // Triangles with a repeated corner, or whose area is below area_epsilon ×
    // (their own longest edge)² or too small for a normal to be computed:
    // judged per triangle, so a mesh's large triangles never condemn its small ones.
    size_t count_degenerate_triangles(float area_epsilon = 1e-12f) const;
};

// Area-weighted vertex normals (replaces existing ones).
void compute_normals(TriangleMesh& mesh);
// Tangents consistent across the mesh without UVs: the direction of a fixed
// world axis projected into each tangent plane, with a fallback axis near the
// poles (no UVs are needed, and the field is smooth where the normal is).
void compute_tangents(TriangleMesh& mesh);

// Checks indices, NaN/Inf positions, empty meshes; throws rsl::Error naming
// `source`. Drops degenerate triangles (zero area) and reports how many via the
// return value (also added to mesh.degenerate_dropped); drops vertices no
// triangle uses; computes normals/tangents when missing or invalid (per vertex:
// valid given ones are kept, renormalized). `kept_vertices` (optional) gets,
// per vertex left, its index before (for attributes the mesh does not hold).
size_t validate_and_complete(TriangleMesh& mesh, const std::filesystem::path& source,
                             std::vector<uint32_t>* kept_vertices = nullptr);

}  // namespace rsl
