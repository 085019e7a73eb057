#include "src/core/skinning.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "src/core/error.h"

namespace rsl {

std::vector<glm::dmat4> segment_joint_matrices(const Scene& scene, int part, float t) {
    const PartSkin& segment = *scene.parts[size_t(part)].skin;
    const Skin& skin = scene.skins[size_t(segment.skin)];
    const size_t s = size_t(segment.joint);
    const glm::dmat4 to_segment = glm::inverse(glm::dmat4(scene.node_world_at(skin.joints[s], t)));
    const glm::dmat4 from_segment = glm::inverse(glm::dmat4(skin.inverse_bind[s]));
    std::vector<glm::dmat4> matrices(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j)
        matrices[j] = j == s ? glm::dmat4(1.0)
                             : to_segment * glm::dmat4(scene.node_world_at(skin.joints[j], t)) *
                                   glm::dmat4(skin.inverse_bind[j]) * from_segment;
    return matrices;
}

void pose_skinned_vertices(const TriangleMesh& mesh, const PartSkin& skin, const std::vector<glm::dmat4>& matrices,
                           PosedVertices& out) {
    const size_t n = mesh.vertex_count();
    RSL_CHECK_EQ(skin.joints.size(), n);
    RSL_CHECK_EQ(skin.weights.size(), n);
    std::vector<Mat4> single(matrices.size());
    for (size_t j = 0; j < matrices.size(); ++j) single[j] = Mat4(matrices[j]);
    out.positions.resize(n);
    out.normals.resize(n);
    out.tangents.resize(mesh.tangents.empty() ? 0 : n);
    const size_t segment = size_t(skin.joint);
    for (size_t v = 0; v < n; ++v) {
        const JointIndices& joints = skin.joints[v];
        const JointWeights& w = skin.weights[v];
        // A vertex on its own joint alone is rigid: kept bit for bit.
        if (w[0] == 1.0f && joints[0] == segment) {
            out.positions[v] = mesh.positions[v];
            out.normals[v] = mesh.normals[v];
            if (!out.tangents.empty()) out.tangents[v] = mesh.tangents[v];
            continue;
        }
        Mat4 blended(0.0f);
        for (int k = 0; k < kJointsPerVertex && w[k] != 0.0f; ++k) blended += w[k] * single[joints[k]];
        const Mat3 linear(blended);
        out.positions[v] = Vec3(blended * Vec4(mesh.positions[v], 1.0f));
        const Vec3 normal = glm::transpose(glm::inverse(linear)) * mesh.normals[v];
        const float length = glm::length(normal);
        out.normals[v] = length > 0.0f ? normal / length : mesh.normals[v];
        if (!out.tangents.empty()) {
            const Vec3 tangent = linear * Vec3(mesh.tangents[v]);
            const float tl = glm::length(tangent);
            out.tangents[v] = tl > 0.0f ? Vec4(tangent / tl, mesh.tangents[v].w) : mesh.tangents[v];
        }
    }
}

void pose_skinned_part(const Scene& scene, int part, float t, PosedVertices& out) {
    const Part& p = scene.parts[size_t(part)];
    RSL_CHECK(p.skin != nullptr);
    pose_skinned_vertices(p.mesh, *p.skin, segment_joint_matrices(scene, part, t), out);
}

BoundingSphere posed_bounding_sphere(const PosedVertices& posed) {
    Bounds box;
    for (const Vec3& p : posed.positions) box.extend(p);
    BoundingSphere sphere;
    if (box.empty()) return sphere;
    sphere.center = box.center();
    float r2 = 0;
    for (const Vec3& p : posed.positions) r2 = std::max(r2, glm::dot(p - sphere.center, p - sphere.center));
    sphere.radius = std::sqrt(r2);
    return sphere;
}

bool has_skinned_parts(const Scene& scene) {
    return std::any_of(scene.parts.begin(), scene.parts.end(), [](const Part& p) { return p.skin != nullptr; });
}

std::vector<std::vector<int>> seam_partners(const Scene& scene) {
    std::map<std::pair<int, int>, int> segment_of;  // (skin, joint) → part
    for (size_t p = 0; p < scene.parts.size(); ++p)
        if (const PartSkin* skin = scene.parts[p].skin.get()) segment_of[{skin->skin, skin->joint}] = int(p);
    std::vector<std::vector<int>> partners(scene.parts.size());
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const PartSkin* skin = scene.parts[p].skin.get();
        if (!skin) continue;
        std::vector<int>& out = partners[p];
        out.assign(skin->joints.size(), -1);
        for (size_t v = 0; v < skin->joints.size(); ++v) {
            float best = 0.0f;
            for (int i = 0; i < kJointsPerVertex; ++i) {
                const int joint = int(skin->joints[v][i]);
                const float w = skin->weights[v][i];
                if (joint == skin->joint || !(w > best)) continue;
                const auto it = segment_of.find({skin->skin, joint});
                if (it == segment_of.end()) continue;  // a joint no vertex is assigned to: no segment
                best = w;
                out[v] = it->second;
            }
        }
    }
    return partners;
}

}  // namespace rsl
