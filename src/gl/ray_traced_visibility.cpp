#include "src/gl/ray_traced_visibility.h"

#include "src/core/error.h"
#include "src/gl/gpu_layout.h"
#include "src/rays/posed_scene.h"

namespace rsl::gl {

void check_gpu_ray_options(const GpuRayOptions& options) {
    if (options.samples_per_side < 1 || options.samples_per_side > GpuRayOptions::kMaxSamplesPerSide)
        throw_error("GPU rays: {} samples per side is outside 1..{}", options.samples_per_side,
                    GpuRayOptions::kMaxSamplesPerSide);
}

RayTracedVisibility::RayTracedVisibility(const Scene& scene, const std::vector<int>& first_vertex) : bvh_(scene) {
    // The vertex pass's six storage blocks, the BVH's three and the border
    // directions: more than the 8 that OpenGL 4.3 promises a compute shader.
    GLint blocks = 0;
    glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &blocks);
    if (blocks < kRayTracedStorageBlocks)
        throw_error("GPU rays need {} storage blocks in a compute shader; this driver allows {} ({})",
                    kRayTracedStorageBlocks, blocks, context_description());
    // Per vertex of the vertex rectangle, its part-space border direction (or 0), as PosedScene moves it.
    std::vector<Vec4> inward(size_t(std::max(first_vertex.back(), 1)), Vec4(0.0f));
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const std::vector<Vec3> directions = border_inward_directions(scene.parts[p].mesh);
        for (size_t v = 0; v < directions.size(); ++v) inward[size_t(first_vertex[p]) + v] = Vec4(directions[v], 0.0f);
    }
    inward_ = make_buffer();
    inward_bytes_ = inward.size() * sizeof(Vec4);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, inward_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(inward_bytes_), inward.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    check_gl("uploading the rays' border directions");
}

void RayTracedVisibility::set_poses(const std::vector<Mat4>& part_to_world) { bvh_.set_poses(part_to_world); }

void RayTracedVisibility::bind(const Program& program) const {
    bvh_.bind(program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingRayInward, inward_.id());
}

size_t RayTracedVisibility::bytes() const { return bvh_.bytes() + inward_bytes_; }

std::string RayTracedVisibility::shader_text() {
    return GpuBvh::shader_defines() + included_shader(kSourceBvhTraverse) + included_shader(kSourceRayVisibility);
}

}  // namespace rsl::gl
