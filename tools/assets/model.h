#pragma once
// A generated model: node hierarchy, one rigid part per mesh node, and a
// looping node animation, held in the same rsl::Scene types the glTF loader
// produces, so a generated model and its file can be compared directly.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "src/core/mesh.h"
#include "src/core/scene.h"

namespace rsl::assets {

// A skinned mesh of a generated model: bind-pose geometry on a node of its
// own, whose vertices blend up to eight joints (glTF JOINTS_0 / WEIGHTS_0, and
// JOINTS_1 / WEIGHTS_1 when a vertex uses more than four).
struct GeneratedSkin {
    std::string name;  // the mesh's and its node's
    TriangleMesh mesh;  // bind space (normals and tangents required)
    std::vector<JointIndices> joints;  // per vertex: indices into joint_nodes
    std::vector<JointWeights> weights; // per vertex
    std::vector<int> joint_nodes;                 // scene nodes
    std::vector<Mat4> inverse_bind;               // per joint: bind space → joint frame
    int material = -1;                            // scene material, or −1
};

struct GeneratedModel {
    Scene scene;             // nodes (rest transform + tracks) and parts (mesh per node)
    std::vector<GeneratedSkin> skins;  // written as skinned meshes (each on a root node named after it)
    float loop_seconds = 0;  // the animation repeats: every node's pose at t equals its pose at t + loop_seconds
    std::string animation_name;

    // Adds a node (and a part when `mesh` has triangles) and returns the node index.
    int add_node(std::string name, int parent, Vec3 translation, TriangleMesh mesh = {});
    int node(std::string_view name) const;  // index by name, throws when absent
    size_t vertex_count() const { return scene.vertex_count(); }
};

// Keys for one loop of a periodic motion: `keys` samples over [0, period),
// then the first key repeated at t = period, so LINEAR playback (slerp for
// rotations) loops without a jump. Consecutive quaternions are kept in the
// same hemisphere so slerp takes the short way.
QuatTrack loop_rotation_track(const std::function<Quat(float t)>& rotation, float period, int keys);
Vec3Track loop_translation_track(const std::function<Vec3(float t)>& translation, float period, int keys);

// Binary glTF 2.0 (.glb): every node with its rest transform, one mesh per
// part (POSITION with min/max, NORMAL, TANGENT, TEXCOORD_0 when the mesh has
// texture coordinates, uint32 indices), and one animation with the nodes'
// tracks. A part whose material is gltf_pbr gets it as a glTF material, its
// base colour texture as an embedded sRGB PNG; each GeneratedSkin as a mesh
// (with JOINTS_0 and WEIGHTS_0) on a root node of its own, and a glTF skin
// with its inverse bind matrices. Written atomically.
void write_glb(const std::filesystem::path& path, const GeneratedModel& model);

// Wavefront OBJ with positions and normals (v, vn, f v//n). Written atomically.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace rsl::assets
