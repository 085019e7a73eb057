#include "src/core/skin_segments.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "src/core/error.h"

namespace rsl {

void normalize_skin_weights(SkinnedMesh& mesh, size_t joint_count, const std::filesystem::path& source,
                            const std::string& what) {
    const size_t n = mesh.mesh.vertex_count();
    if (mesh.joints.size() != n || mesh.weights.size() != n)
        throw_file_error(source, "{}: {} joint and {} weight sets for {} vertices", what, mesh.joints.size(),
                         mesh.weights.size(), n);
    for (size_t v = 0; v < n; ++v) {
        JointIndices& joints = mesh.joints[v];
        JointWeights& w = mesh.weights[v];
        float sum = 0;
        for (int k = 0; k < kJointsPerVertex; ++k) {
            if (!std::isfinite(w[k]) || w[k] < 0)
                throw_file_error(source, "{}: vertex {} has weight {} (WEIGHTS_{} must be finite and ≥ 0)", what, v, w[k],
                                 k / 4);
            if (w[k] > 0 && joints[k] >= joint_count)
                throw_file_error(source, "{}: vertex {} uses joint {}, out of range for its skin's {} joints", what, v,
                                 joints[k], joint_count);
            sum += w[k];
        }
        if (!(sum > 0)) throw_file_error(source, "{}: vertex {} has all its WEIGHTS_0 zero", what, v);
        // Slots by decreasing weight (ties: lower joint first), so slot 0 is the vertex's segment.
        std::array<int, kJointsPerVertex> order;
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
            return w[a] != w[b] ? w[a] > w[b] : joints[a] < joints[b];
        });
        const JointIndices old_joints = joints;
        const JointWeights old_w = w;
        for (int k = 0; k < kJointsPerVertex; ++k) {
            w[k] = old_w[order[k]] / sum;
            joints[k] = w[k] > 0 ? old_joints[order[k]] : old_joints[order[0]];
        }
    }
}

std::vector<SkinSegment> split_skinned_mesh(const SkinnedMesh& skinned, const Skin& skin) {
    const TriangleMesh& mesh = skinned.mesh;
    const size_t joint_count = skin.joints.size();
    // Each triangle's joint: the largest summed weight over its corners.
    std::vector<int> triangle_joint(mesh.triangle_count());
    std::vector<float> sums(joint_count, 0.0f);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.indices[3 * t + size_t(c)];
            for (int k = 0; k < kJointsPerVertex; ++k) sums[skinned.joints[v][k]] += skinned.weights[v][k];
        }
        int best = -1;
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.indices[3 * t + size_t(c)];
            for (int k = 0; k < kJointsPerVertex; ++k) {
                const int j = skinned.joints[v][k];
                if (best < 0 || sums[j] > sums[best] || (sums[j] == sums[best] && j < best)) best = j;
            }
        }
        triangle_joint[t] = best;
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.indices[3 * t + size_t(c)];
            for (int k = 0; k < kJointsPerVertex; ++k) sums[skinned.joints[v][k]] = 0.0f;
        }
    }

    std::vector<SkinSegment> segments;
    std::vector<uint32_t> local(mesh.vertex_count());
    std::vector<int> stamp(mesh.vertex_count(), -1);
    for (size_t j = 0; j < joint_count; ++j) {
        SkinSegment segment;
        segment.joint = int(j);
        const Mat4& to_joint = skin.inverse_bind[j];
        const Mat3 linear(to_joint);
        const Mat3 normal_matrix = glm::transpose(glm::inverse(linear));
        TriangleMesh& out = segment.mesh;
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            if (triangle_joint[t] != int(j)) continue;
            for (int c = 0; c < 3; ++c) {
                const uint32_t v = mesh.indices[3 * t + size_t(c)];
                if (stamp[v] != int(j)) {
                    stamp[v] = int(j);
                    local[v] = uint32_t(out.positions.size());
                    out.positions.push_back(Vec3(to_joint * Vec4(mesh.positions[v], 1.0f)));
                    out.normals.push_back(glm::normalize(normal_matrix * mesh.normals[v]));
                    if (!mesh.tangents.empty()) {
                        const Vec4& tangent = mesh.tangents[v];
                        out.tangents.emplace_back(glm::normalize(linear * Vec3(tangent)), tangent.w);
                    }
                    if (!mesh.texcoords.empty()) out.texcoords.push_back(mesh.texcoords[v]);
                    segment.skin.joints.push_back(skinned.joints[v]);
                    segment.skin.weights.push_back(skinned.weights[v]);
                }
                out.indices.push_back(local[v]);
            }
        }
        if (out.indices.empty()) continue;
        segment.skin.joint = int(j);
        segments.push_back(std::move(segment));
    }
    return segments;
}

}  // namespace rsl
