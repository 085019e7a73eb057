#pragma once
// Linear blend skinning of a skinned mesh's segments (docs/design/SKINNING.md).
// A segment is a rigid part placed by its joint's world matrix W_s; its mesh
// holds the bind-pose geometry in that joint's frame, p_s = IBM_s · p_bind.
// At time t its vertices blend the skin's joints as glTF specifies,
//   P_world = Σ_j w_j · W_j · IBM_j · p_bind,
// and the renderers take them in the segment's own frame,
//   p'_s = W_s⁻¹ · P_world = Σ_j w_j · R_j · p_s,  R_j = W_s⁻¹ · W_j · IBM_j · IBM_s⁻¹,
// so that the part's transform, its fields and everything rigid stay as they
// are, and a vertex weighted to its own joint alone does not move (R_s = I).
#include <vector>

#include "src/core/scene.h"

namespace rsl {

// A skinned part's vertices at one time, in the part's own frame.
struct PosedVertices {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;   // unit: the blended matrix's inverse transpose times the bind normal
    std::vector<Vec4> tangents;  // empty when the mesh has none; xyz unit (not re-orthogonalized), w kept
};

// The matrices R_j (above) of `part`'s skin at time t, one per skin joint, in
// double precision; R_s is the identity.
std::vector<glm::dmat4> segment_joint_matrices(const Scene& scene, int part, float t);

// Poses a skinned part (part.skin set) at time t into `out` (resized).
void pose_skinned_part(const Scene& scene, int part, float t, PosedVertices& out);

// The same from given matrices (segment_joint_matrices), for callers that pose
// many parts of one skin.
void pose_skinned_vertices(const TriangleMesh& mesh, const PartSkin& skin, const std::vector<glm::dmat4>& matrices,
                           PosedVertices& out);

// The posed vertices' bounding sphere, centred on their box as
// TriangleMesh::bounding_sphere.
BoundingSphere posed_bounding_sphere(const PosedVertices& posed);

// Whether any part of the scene is skinned.
bool has_skinned_parts(const Scene& scene);

// Per part, per vertex: the segment whose joint the vertex blends with the
// largest weight after its own (a seam vertex), or -1; empty for a rigid
// part. A seam vertex lies on its neighbour's surface, where that
// neighbour's OVDF is coarsest, so the renderers leave that one occluder
// out of its sum (docs/design/SKINNING.md "Visibility at the joints").
std::vector<std::vector<int>> seam_partners(const Scene& scene);

}  // namespace rsl
