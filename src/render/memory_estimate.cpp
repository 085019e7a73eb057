#include "src/render/memory_estimate.h"

#include <algorithm>
#include <array>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "src/brdf/pbr_basis.h"
#include "src/core/memory_limit.h"
#include "src/fields/field_cache.h"

namespace rsl {
namespace {

// Per vertex of every part: the mesh, posed positions and normals, the
// vertex blocks, colours and the renderer's per-vertex lists (measured on
// 10,000 instanced parts: 340 bytes a vertex).
constexpr uint64_t kRenderBytesPerVertex = 400;
constexpr uint64_t kRenderBytesPerPart = 16 * 1024;
// A skinned vertex also carries its joints and weights (48 bytes) and is
// posed every frame into positions, normals and tangents (40 bytes), by the
// renderer and again by the posed scene that forms the image.
constexpr uint64_t kSkinnedBytesPerVertex = sizeof(JointIndices) + sizeof(JointWeights) + 2 * 40;
// The program, Embree's and TBB's start-up, and the tables every render
// loads whatever the scene.
constexpr uint64_t kBaseBytes = 64ull << 20;
// One BRDF table (96² × 64 views, src/brdf/brdf_table.h): about 15 MB.
constexpr uint64_t kBrdfTableBytes = 16ull << 20;
// The light fit holds about 700 bytes a cube-map texel (src/core/envmap.h).
constexpr uint64_t kFitBytesPerTexel = 700;

// The clustered-PCA model of `samples` samples of `dims` values: tables,
// cluster indices and coefficients (src/fields/cpca.h).
uint64_t cpca_bytes(uint64_t samples, uint64_t dims, uint64_t clusters, uint64_t vectors) {
    return std::min(clusters, samples) * dims * (vectors + 1) * 4 + samples * (vectors + 1) * 4;
}

}  // namespace

MemoryEstimate estimate_render_memory(const Scene& scene, bool self_visibility, bool occluders, int image_width,
                                      int image_height) {
    uint64_t vertices = 0, skinned = 0;
    for (const Part& part : scene.parts) {
        vertices += part.mesh.vertex_count();
        if (part.skin) skinned += part.mesh.vertex_count();
    }
    uint64_t bytes = kBaseBytes + kRenderBytesPerVertex * vertices + kSkinnedBytesPerVertex * skinned +
                     kRenderBytesPerPart * scene.parts.size();

    // Fields: every unique mesh's resident model, plus the largest bake's
    // working set (the traced tables before compression).
    const PrecomputeSettings& p = scene.precompute;
    const std::vector<MeshInstances> unique = group_instances(scene);
    uint64_t resident = 0, largest_bake = 0;
    for (const MeshInstances& group : unique) {
        const uint64_t v = scene.parts[size_t(group.parts.front())].mesh.vertex_count();
        if (self_visibility) {
            const uint64_t dims = uint64_t(p.svdf_resolution) * uint64_t(p.svdf_resolution);
            resident += cpca_bytes(v, dims, uint64_t(p.svdf_clusters), uint64_t(p.svdf_vectors));
            largest_bake = std::max(largest_bake, 2 * v * dims * 4);  // traced tables, and the fit's copy
        }
        if (occluders) {
            const uint64_t samples = uint64_t(p.ovdf_shells + 2) * 6 * uint64_t(p.ovdf_cube_resolution) *
                                     uint64_t(p.ovdf_cube_resolution);
            const uint64_t dims = uint64_t(p.ovdf_vdt_resolution) * uint64_t(p.ovdf_vdt_resolution);
            const uint64_t segments = uint64_t(p.ovdf_shells + 2) * 6 * 4;
            resident += cpca_bytes(samples, dims, segments, uint64_t(p.ovdf_vectors));
            const uint64_t threads = std::max(1u, std::thread::hardware_concurrency());  // segments bake in parallel
            largest_bake = std::max(largest_bake, samples / segments * dims * 4 * threads);
        }
    }
    bytes += resident + largest_bake;

    std::set<int> materials;
    for (const Part& part : scene.parts) materials.insert(part.material);
    bytes += kBrdfTableBytes * materials.size();
    // Materials varying per point share the basis tables (src/brdf/pbr_basis.h)
    // of the roughness levels their textures reach.
    std::array<bool, kPbrLevels> dielectric{}, metal{};
    bool any_varying = false;
    for (const int m : materials) {
        if (m < 0 || size_t(m) >= scene.materials.size() || !varies_per_point(scene.materials[size_t(m)])) continue;
        const PbrLevelRange range = pbr_level_range(scene.materials[size_t(m)]);
        any_varying = true;
        for (int j = range.first; j <= range.last; ++j) dielectric[size_t(j)] = true, metal[size_t(j)] |= range.metal;
    }
    if (any_varying) {
        uint64_t basis = 1;
        for (int j = 0; j < kPbrLevels; ++j) basis += (dielectric[size_t(j)] ? 1 : 0) + (metal[size_t(j)] ? 1 : 0);
        bytes += kBrdfTableBytes * basis;
    }

    if (scene.environment.present()) {
        const uint64_t texels = 6ull * uint64_t(scene.environment.resolution) * uint64_t(scene.environment.resolution);
        bytes += kFitBytesPerTexel * texels * (scene.environment.second_file.empty() ? 1 : 2);
    }
    const int width = image_width > 0 ? image_width : scene.camera.width;
    const int height = image_height > 0 ? image_height : scene.camera.height;
    bytes += image_memory_bytes(width, height);
    const std::string skinned_note = skinned ? fmt::format(" ({} skinned)", skinned) : std::string();
    return {bytes, fmt::format("{} vertices{} in {} parts, {} unique meshes' fields, {} materials, a {}×{} image",
                               vertices, skinned_note, scene.parts.size(), unique.size(), materials.size(), width,
                               height)};
}

void check_render_memory(const Scene& scene, bool self_visibility, bool occluders, int image_width,
                         int image_height) {
    const MemoryEstimate estimate =
        estimate_render_memory(scene, self_visibility, occluders, image_width, image_height);
    check_memory_estimate(estimate.bytes, scene.source, estimate.what);
}

}  // namespace rsl
