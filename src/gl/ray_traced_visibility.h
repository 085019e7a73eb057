#pragma once
// The ray-traced baseline's GPU state (RenderOptions::gpu_rays;
// docs/design/GPU_DESIGN.md "Ray-traced visibility"): the posed parts' BVH
// (gpu_bvh.h) and each vertex's border direction, from which the vertex
// pass traces the CPU ray-traced rows' rays (shaders/ray_visibility.glsl).
#include <string>
#include <vector>

#include "src/core/scene.h"
#include "src/gl/gl_objects.h"
#include "src/gl/gpu_bvh.h"
#include "src/render/render_options.h"

namespace rsl::gl {

// Storage blocks of the vertex pass with RAY_TRACED (the test-only recording adds two).
inline constexpr int kRayTracedStorageBlocks = 12;

// Throws rsl::Error for S outside 1..GpuRayOptions::kMaxSamplesPerSide.
void check_gpu_ray_options(const GpuRayOptions& options);

class RayTracedVisibility {
public:
    // `first_vertex`: per part its first vertex in the vertex rectangle
    // (PackedGeometry::first_vertex). Needs a current OpenGL ≥ 4.3 context.
    RayTracedVisibility(const Scene& scene, const std::vector<int>& first_vertex);

    // The parts' poses of the frame (part → world, scene.parts order).
    void set_poses(const std::vector<Mat4>& part_to_world);
    // The BVH's storage buffers and uniforms and the border directions, for
    // the vertex pass `program` (the current program).
    void bind(const Program& program) const;
    const GpuBvh& bvh() const { return bvh_; }
    size_t bytes() const;
    // What RAY_TRACED adds to the vertex pass's source: the traversal, then the rays.
    static std::string shader_text();

private:
    GpuBvh bvh_;
    Buffer inward_;
    size_t inward_bytes_ = 0;
};

}  // namespace rsl::gl
