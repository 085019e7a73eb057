#pragma once
// Splitting a skinned mesh into rigid segments, one per joint that dominates
// some of its vertices (docs/design/SKINNING.md, "Segments"):
// - a vertex belongs to the joint of its largest weight (ties: the lowest
//   joint index);
// - a triangle belongs to the joint with the largest sum of weights over its
//   three corners (ties: the lowest joint index), so a triangle across a
//   joint goes to the side that moves it most;
// - a segment holds its triangles and every vertex they use, a corner of a
//   neighbouring segment's vertex copied (it blends the same joints, so the
//   posed surface stays closed).
// A segment's geometry is in its joint's frame (the joint's inverse bind
// matrix applied), so it bakes and moves like any rigid part.
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "src/core/mesh.h"
#include "src/core/scene.h"

namespace rsl {

// A validated mesh in bind space with its skin attributes per vertex.
struct SkinnedMesh {
    TriangleMesh mesh;
    std::vector<JointIndices> joints;  // JOINTS_0 (and JOINTS_1)
    std::vector<JointWeights> weights; // WEIGHTS_0 (and WEIGHTS_1)
};

struct SkinSegment {
    int joint = -1;     // index into the skin's joints
    TriangleMesh mesh;  // in the joint's frame
    PartSkin skin;      // joints and normalized weights per vertex of `mesh`; skin.skin left to the caller
};

// Normalizes each vertex's weights to sum 1 (zero slots' joints set to the
// first slot's) and checks them: finite, ≥ 0, not all 0, joints in range of
// `joint_count`. Throws rsl::Error naming `source` and `what` (the mesh).
void normalize_skin_weights(SkinnedMesh& mesh, size_t joint_count, const std::filesystem::path& source,
                            const std::string& what);

// The segments of a mesh (weights normalized), in increasing joint order;
// joints that dominate no triangle have none.
std::vector<SkinSegment> split_skinned_mesh(const SkinnedMesh& mesh, const Skin& skin);

}  // namespace rsl
