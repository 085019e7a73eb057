#pragma once
// A two-level BVH of a scene's rigid parts on the GPU, for shadow rays in
// compute shaders (shaders/bvh_traverse.glsl; docs/design/GPU_DESIGN.md
// "Ray-traced visibility"):
//  * one bottom level per unique mesh (field_cache.h group_instances), in
//    the mesh's frame, built once on the CPU (binned SAH, src/rays/bvh_builder.h)
//    and shared by the parts that use the mesh, as the fields are;
//  * a top level over the parts, its topology built at the first pose and
//    its boxes refit on the GPU at every set_poses (shaders/bvh_refit.comp.glsl).
// Occlusion queries reproduce RayScene's (origins_outside_surfaces = true):
// the same hits are ignored near a ray's origin, so GPU and Embree agree but
// where a ray grazes an edge.
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/scene.h"
#include "src/gl/gl_objects.h"
#include "src/gl/gpu_interface.h"

namespace rsl::gl {

// vec4 per node (both children: lo + index, hi + count), per triangle (v0,
// e1, e2) and per part's instance record (inverse, transform, mesh box with
// root, diagonal and exit distance).
inline constexpr int kBvhNodeVec4s = 4;
inline constexpr int kBvhTriangleVec4s = 3;
inline constexpr int kBvhInstanceVec4s = 11;
// Stack entries of the traversal per level; the builder's depth limit keeps within it.
inline constexpr int kBvhStack = 32;

struct BvhStats {
    size_t meshes = 0, triangles = 0, bottom_nodes = 0, top_nodes = 0;
    int bottom_depth = 0, top_depth = 0;
    double build_ms = 0;  // the bottom levels, on the CPU
};

class GpuBvh {
public:
    // Needs a current OpenGL ≥ 4.3 context for its lifetime.
    explicit GpuBvh(const Scene& scene);
    // Part → world per part (scene.parts order): the instance records, then
    // the top level's boxes refit on the GPU (its topology is the first pose's).
    void set_poses(const std::vector<Mat4>& part_to_world);
    // Its three storage buffers at kBindingBvh* (gpu_interface.h), and the uniforms of
    // bvh_traverse.glsl into `program` (the current program).
    void bind(const Program& program) const;
    size_t bytes() const { return bytes_; }
    const BvhStats& stats() const { return stats_; }
    // What a shader that includes bvh_traverse.glsl needs first, besides the
    // bindings (shader_interface_glsl): its sizes as macros.
    static std::string shader_defines();

    // Whether each ray (origin, direction) is blocked before t_far (in units
    // of the direction's length), by shaders/trace_rays.comp.glsl: the test's
    // and `rsl truth`'s entry point. After set_poses.
    std::vector<uint8_t> occluded(const std::vector<Vec3>& origins, const std::vector<Vec3>& directions,
                                  float t_far) const;

private:
    void build_top(const std::vector<Bounds>& world_boxes);

    size_t parts_ = 0;
    std::vector<Vec4> nodes_;     // bottom levels, then the top level's (from top_first_)
    std::vector<Vec4> instances_;  // per part kBvhInstanceVec4s, then the top level's part order
    std::vector<int> part_root_;   // per part: its mesh's root node
    std::vector<Bounds> part_box_; // per part: its mesh's box (part space)
    int top_first_ = 0;            // the top level's first node
    bool top_built_ = false;
    std::vector<int> refit_levels_;  // top nodes, deepest level first
    std::vector<int> level_ends_;    // per level, its end in refit_levels_
    Buffer nodes_buffer_, triangles_buffer_, instances_buffer_, levels_buffer_;
    Program refit_;
    mutable Program trace_;
    size_t bytes_ = 0;
    BvhStats stats_;
};

}  // namespace rsl::gl
