#pragma once
// Subdivision at load: per-vertex shading (and the per-vertex SVDF) only sees
// light and shadow where there are vertices, so a box of a few hundred
// vertices shades its faces by interpolating across metre-long triangles.
// Long edges are split until every edge is at most a target length
// (docs/SCENE_FORMAT.md, "subdivision").
#include <filesystem>

#include "src/core/mesh.h"

namespace rsl {

// The scene file's `subdivision` setting. The target edge of a mesh is
// `relative_edge` × its bounding-sphere radius, or `absolute_edge` (in the
// mesh's own units) when that is set (> 0); off when !enabled.
struct SubdivisionSettings {
    // On unless the scene file says `false`: it lowers the image error of
    // coarse meshes and leaves fine ones unchanged (docs/SCENE_FORMAT.md,
    // "Subdivision"). Bare .obj/.gltf files, which have no scene file to
    // switch it off, load as they are.
    bool enabled = true;
    // With it on: the image error stops falling at R/4–R/8, the worst box's
    // per-vertex error keeps falling to R/8, and R/16 costs 3× more.
    float relative_edge = 0.125f;
    float absolute_edge = 0;
    float target_edge(const TriangleMesh& mesh) const;
};

// Meshes whose subdivision would exceed this many triangles are refused (a
// tiny `absolute_edge` on a big part is a typo, not a wish for 100 GB).
inline constexpr size_t kMaxSubdividedTriangles = size_t(1) << 24;

// Splits edges longer than `target_edge` at their midpoints, pass after pass,
// until none is longer: each triangle becomes 2, 3 or 4 according to how many
// of its edges are split. An edge is split once for every triangle that uses
// it (one midpoint vertex per vertex pair), so the mesh stays watertight, and
// the midpoint depends only on the edge's end positions, so vertices split at
// a crease (same position, other normal) get coincident midpoints that stay
// split. New vertices take the mean of their endpoints' attributes (normal
// and tangent renormalized, the tangent re-orthogonalized). Returns the
// number of vertices added. Throws rsl::Error naming `source` when the result
// would exceed kMaxSubdividedTriangles.
size_t subdivide_long_edges(TriangleMesh& mesh, float target_edge, const std::filesystem::path& source);

// A loaded part's memory, for the estimate made before the parts' meshes are
// built (src/core/memory_limit.h): positions, normals, tangents, texture
// coordinates and about two triangles a vertex, with the vectors' slack.
inline constexpr size_t kMeshBytesPerVertex = 96;
inline constexpr size_t kMeshBytesPerPart = 1024;

// Applies `settings` to a loaded mesh (nothing when off or when no edge is
// longer than the target); returns the vertices added.
size_t subdivide_for_shading(TriangleMesh& mesh, const SubdivisionSettings& settings,
                             const std::filesystem::path& source);

}  // namespace rsl
