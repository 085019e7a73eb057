#include "src/gl/gpu_bvh.h"

#include <chrono>
#include <cstring>
#include <fmt/core.h>

#include "src/core/error.h"
#include "src/fields/field_cache.h"
#include "src/gl/gl_renderer_units.h"
#include "src/rays/bvh_builder.h"
#include "src/shading/ray_samples.h"

namespace rsl::gl {

namespace {

// An int in a float's bits (node indices and counts ride in the boxes' w).
float int_bits(int x) {
    float f;
    std::memcpy(&f, &x, sizeof f);
    return f;
}

// A BvhTree's nodes, appended to `out` as kBvhNodeVec4s vec4 each: child
// node indices offset by `node_base`, leaf ranges by `leaf_base`.
void append_nodes(const BvhTree& tree, int node_base, int leaf_base, std::vector<Vec4>& out) {
    for (const BvhNode& node : tree.nodes)
        for (const BvhChild& c : node.child) {
            // An empty child: a point box at 10³⁰, which no ray reaches before
            // t_far (an inverted box would pass the slab test).
            const Vec3 lo = c.box.empty() ? Vec3(1e30f) : c.box.lo, hi = c.box.empty() ? Vec3(1e30f) : c.box.hi;
            out.push_back(Vec4(lo, int_bits(c.count > 0 ? leaf_base + c.index : node_base + c.index)));
            out.push_back(Vec4(hi, int_bits(c.count)));
        }
}

// The part's box in the world: its mesh box's eight corners posed (RayScene::commit's).
Bounds posed_box(const Bounds& b, const Mat4& transform) {
    Bounds box;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y, (corner & 4) ? b.hi.z : b.lo.z);
        box.extend(Vec3(transform * Vec4(p, 1.0f)));
    }
    return box;
}

void upload(Buffer& buffer, const void* data, size_t bytes, GLenum usage) {
    if (!buffer) buffer = make_buffer();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(bytes, 16)), bytes ? data : nullptr, usage);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

}  // namespace

std::string GpuBvh::shader_defines() {
    // Array sizes in GLSL 4.30 want literals: the constants as macros.
    return fmt::format("#define BVH_NODE_VEC4S {}\n#define BVH_TRIANGLE_VEC4S {}\n#define BVH_INSTANCE_VEC4S {}\n"
                       "#define BVH_STACK {}\n",
                       kBvhNodeVec4s, kBvhTriangleVec4s, kBvhInstanceVec4s, kBvhStack);
}

GpuBvh::GpuBvh(const Scene& scene) : parts_(scene.parts.size()) {
    const auto start = std::chrono::steady_clock::now();
    part_root_.assign(parts_, 0);
    part_box_.assign(parts_, Bounds{});
    std::vector<Vec4> triangles;
    BvhBuildOptions options;
    options.max_depth = kBvhStack - 2;
    for (const MeshInstances& group : group_instances(scene)) {
        const TriangleMesh& mesh = scene.parts[size_t(group.parts.front())].mesh;
        const BvhTree tree = build_bvh(triangle_boxes(mesh), options);
        const int root = int(nodes_.size()) / kBvhNodeVec4s;
        append_nodes(tree, root, int(triangles.size()) / kBvhTriangleVec4s, nodes_);
        for (const int t : tree.order) {  // leaf order: a leaf's triangles are consecutive
            const uint32_t* corner = &mesh.indices[3 * size_t(t)];
            const Vec3 p0 = mesh.positions[corner[0]], p1 = mesh.positions[corner[1]], p2 = mesh.positions[corner[2]];
            triangles.push_back(Vec4(p0, 0.0f));
            triangles.push_back(Vec4(p1 - p0, 0.0f));
            triangles.push_back(Vec4(p2 - p0, 0.0f));
        }
        for (const int part : group.parts) part_root_[size_t(part)] = root, part_box_[size_t(part)] = mesh.bounds();
        ++stats_.meshes;
        stats_.triangles += mesh.triangle_count();
        stats_.bottom_depth = std::max(stats_.bottom_depth, tree.depth);
    }
    stats_.bottom_nodes = nodes_.size() / kBvhNodeVec4s;
    stats_.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    top_first_ = int(stats_.bottom_nodes);
    upload(triangles_buffer_, triangles.data(), triangles.size() * sizeof(Vec4), GL_STATIC_DRAW);
    bytes_ = triangles.size() * sizeof(Vec4);
    refit_ = build_compute_program("bvh_refit.comp.glsl", shader_interface_glsl() + shader_defines());
    check_gl("building the BVH");
}

// The top level's topology over the parts' boxes of the first pose, and the
// order in which the refit pass visits its nodes (deepest level first).
void GpuBvh::build_top(const std::vector<Bounds>& world_boxes) {
    BvhBuildOptions options;
    options.max_leaf = 1;
    options.max_depth = kBvhStack - 2;
    const BvhTree tree = build_bvh(world_boxes, options);
    nodes_.resize(size_t(top_first_) * kBvhNodeVec4s);
    append_nodes(tree, top_first_, 0, nodes_);
    stats_.top_nodes = tree.nodes.size();
    stats_.top_depth = tree.depth;
    // The part order of the leaves, four to a vec4 (exact as floats below 2²⁴).
    instances_.assign(parts_ * kBvhInstanceVec4s + (parts_ + 3) / 4, Vec4(0.0f));
    for (size_t i = 0; i < tree.order.size(); ++i)
        instances_[parts_ * kBvhInstanceVec4s + i / 4][int(i % 4)] = float(tree.order[i]);
    // Levels by breadth-first order, then reversed: children before parents.
    std::vector<std::vector<int>> levels{{0}};
    while (true) {
        std::vector<int> next;
        for (const int n : levels.back())
            for (const BvhChild& c : tree.nodes[size_t(n)].child)
                if (c.count == 0 && !c.box.empty()) next.push_back(c.index);
        if (next.empty()) break;
        levels.push_back(std::move(next));
    }
    // bvh_refit.comp.glsl holds kBvhStack level ends; the depth limit keeps within them.
    RSL_CHECK(int(levels.size()) <= kBvhStack);
    refit_levels_.clear(), level_ends_.clear();
    for (auto level = levels.rbegin(); level != levels.rend(); ++level) {
        for (const int n : *level) refit_levels_.push_back(top_first_ + n);
        level_ends_.push_back(int(refit_levels_.size()));
    }
    upload(nodes_buffer_, nodes_.data(), nodes_.size() * sizeof(Vec4), GL_DYNAMIC_DRAW);
    upload(levels_buffer_, refit_levels_.data(), refit_levels_.size() * sizeof(int), GL_STATIC_DRAW);
    bytes_ += nodes_.size() * sizeof(Vec4) + refit_levels_.size() * sizeof(int);
    top_built_ = true;
}

void GpuBvh::set_poses(const std::vector<Mat4>& part_to_world) {
    RSL_CHECK_EQ(part_to_world.size(), parts_);
    std::vector<Bounds> world_boxes(parts_);
    for (size_t p = 0; p < parts_; ++p) world_boxes[p] = posed_box(part_box_[p], part_to_world[p]);
    if (!top_built_) build_top(world_boxes);
    for (size_t p = 0; p < parts_; ++p) {
        Vec4* record = &instances_[p * kBvhInstanceVec4s];
        const Mat4 inverse = glm::inverse(part_to_world[p]);
        for (int c = 0; c < 4; ++c) record[c] = inverse[c], record[4 + c] = part_to_world[p][c];
        record[8] = Vec4(part_box_[p].lo, int_bits(part_root_[p]));
        record[9] = Vec4(part_box_[p].hi, 0.0f);
        // RayScene's instance diagonal and exit distance, from the same box.
        const float diagonal = glm::length(world_boxes[p].hi - world_boxes[p].lo);
        record[10] = Vec4(diagonal, shading::kRayExitOffsets * shading::kRayOffsetOfScale * diagonal, 0.0f, 0.0f);
    }
    upload(instances_buffer_, instances_.data(), instances_.size() * sizeof(Vec4), GL_DYNAMIC_DRAW);
    // The refit: one workgroup, level by level (bvh_refit.comp.glsl).
    glUseProgram(refit_.id());
    glUniform1i(uniform(refit_, "u_level_count"), int(level_ends_.size()));
    glUniform1iv(uniform(refit_, "u_level_ends"), GLsizei(level_ends_.size()), level_ends_.data());
    glUniform1i(uniform(refit_, "u_parts"), int(parts_));
    bind(refit_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingBvhLevels, levels_buffer_.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    check_gl("refitting the BVH");
}

void GpuBvh::bind(const Program& program) const {
    glUniform1i(uniform(program, "u_bvh_top_root"), top_first_);
    glUniform1i(uniform(program, "u_bvh_parts"), int(parts_));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingBvhNodes, nodes_buffer_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingBvhTriangles, triangles_buffer_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingBvhInstances, instances_buffer_.id());
}

std::vector<uint8_t> GpuBvh::occluded(const std::vector<Vec3>& origins, const std::vector<Vec3>& directions,
                                      float t_far) const {
    RSL_CHECK_EQ(origins.size(), directions.size());
    RSL_CHECK(top_built_);
    if (!trace_)
        trace_ = build_compute_program("trace_rays.comp.glsl", shader_defines() + shading_prelude() +
                                                                   included_shader(kSourceBvhTraverse));
    std::vector<Vec4> rays;
    for (size_t i = 0; i < origins.size(); ++i) rays.push_back(Vec4(origins[i], 0.0f)), rays.push_back(Vec4(directions[i], 0.0f));
    Buffer ray_buffer, hit_buffer;
    upload(ray_buffer, rays.data(), rays.size() * sizeof(Vec4), GL_STATIC_DRAW);
    upload(hit_buffer, nullptr, origins.size() * sizeof(uint32_t), GL_DYNAMIC_READ);
    glUseProgram(trace_.id());
    glUniform1i(uniform(trace_, "u_ray_count"), int(origins.size()));
    glUniform1f(uniform(trace_, "u_t_far"), t_far);
    bind(trace_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingRays, ray_buffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingHits, hit_buffer.id());
    const GLuint groups = GLuint((origins.size() + 63) / 64);
    glDispatchCompute(std::max<GLuint>(groups, 1), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<uint32_t> hits(origins.size());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, hit_buffer.id());
    if (!hits.empty()) glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(hits.size() * 4), hits.data());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    check_gl("tracing rays");
    return std::vector<uint8_t>(hits.begin(), hits.end());
}

}  // namespace rsl::gl
