// Set-up and per-frame state of the CPU renderer; the per-block shading kernel
// is in shade_block.cpp.
#include "src/render/renderer.h"

#include <atomic>

#include <tbb/parallel_for.h>

#include "lightfit/decompose.h"
#include "src/core/error.h"
#include "src/render/ovdf_occluder.h"
#include "src/core/sphere_light.h"

namespace rsl {

namespace {
constexpr int kBlockSize = 256;  // must match shade_block.cpp's scratch size
}

RslSet fit_environment_lights(const CubeMap& environment, int lights, bool cross_face) {
    lightfit::DecomposeOptions options;
    options.lights = lights;
    options.cross_face = cross_face;
    return lightfit::decompose(environment, options);
}

void check_part_fields(const Scene& scene, PartFields& fields) {
    const size_t parts = scene.parts.size();
    if (parts == 0) throw_file_error(scene.source, "scene '{}' has no parts", scene.name);
    fields.self.resize(parts);
    fields.occluder.resize(parts);
    for (size_t p = 0; p < parts; ++p)
        if (fields.self[p] && size_t(fields.self[p]->vertex_count()) != scene.parts[p].mesh.vertex_count())
            throw_file_error(scene.source, "part '{}': its SVDF has {} vertices, the mesh {}", scene.parts[p].name,
                             fields.self[p]->vertex_count(), scene.parts[p].mesh.vertex_count());
}

Renderer::Renderer(const Scene& scene, RslSet environment_lights, PartFields fields, const RenderOptions& options)
    : scene_(scene),
      options_(options),
      rsls_(std::move(environment_lights)),
      fields_(std::move(fields)),
      materials_(scene, options) {
    const size_t parts = scene.parts.size();
    check_part_fields(scene, fields_);
    for (size_t p = 0; p < parts; ++p) {
        const Part& part = scene.parts[p];
        const size_t n = part.mesh.vertex_count();
        if (part.mesh.normals.size() != n)
            throw_file_error(scene.source, "part '{}' has {} normals for {} vertices", part.name,
                             part.mesh.normals.size(), n);
        for (size_t begin = 0; begin < n; begin += kBlockSize)
            blocks_.push_back(Block{int(p), int(begin), int(std::min(n, begin + kBlockSize))});
        local_bounds_.push_back(part.mesh.bounding_sphere());
        local_boxes_.push_back(part.mesh.bounds());
        local_reach_.push_back(fields_.occluder[p] ? fields_.occluder[p]->reach() : BoundingSphere{});
        culling_parts_.emplace_back();
        culling_parts_.back().field = fields_.occluder[p].get();
        culling_parts_.back().local_reach = local_reach_.back();
        // Compressed OVDFs blended by coefficients take the split lookup.
        const auto* ovdf = dynamic_cast<const OvdfOccluder*>(fields_.occluder[p].get());
        const bool fast = options_.fast_occluder_lookups && ovdf && ovdf->blend() == OvdfBlend::AlignedCoefficients;
        fast_lookups_.push_back(fast ? std::make_unique<const OvdfLookup>(ovdf->field()) : nullptr);
        if (fast_lookups_.back() && !fast_lookups_.back()->usable()) fast_lookups_.back().reset();
    }
    for (const LocalLight& light : scene.lights) {
        if (!(light.radius > 0.0f)) throw_file_error(scene.source, "local light with radius {}", light.radius);
        light_radiance_.push_back(sphere_light_radiance(light));
    }
    poses_.resize(parts);
    environment_squares_.resize(rsls_.lights.size());
    light_positions_.resize(scene.lights.size());
    const size_t light_count = rsls_.lights.size() + scene.lights.size();
    occluders_.reserve(parts * light_count * (parts - 1));
    set_time(0.0f);
}

void Renderer::set_time(float t) {
    time_ = t;
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        PartPose& pose = poses_[p];
        pose.transform = scene_.part_transform_at(int(p), t);
        pose.linear = Mat3(pose.transform);
        pose.normal = glm::transpose(glm::inverse(pose.linear));
        pose.inverse = glm::inverse(pose.transform);
        pose.inverse_linear = Mat3(pose.inverse);
        for (int a = 0; a < 3; ++a)
            pose.face_scale[a] = glm::length(Vec3(pose.inverse_linear[0][a], pose.inverse_linear[1][a], pose.inverse_linear[2][a]));
        const Vec3 axes(glm::length(pose.linear[0]), glm::length(pose.linear[1]), glm::length(pose.linear[2]));
        pose.uniform_scale = std::max({axes.x, axes.y, axes.z}) <= (1.0f + 1e-4f) * std::min({axes.x, axes.y, axes.z});
        pose.world_bounds = transform_sphere(pose.transform, local_bounds_[p]);
    }
    const Mat3 rotation = scene_.environment.rotation_at(t);
    for (size_t l = 0; l < rsls_.lights.size(); ++l) {
        const RotatableSquareLight& rsl = rsls_.lights[l];
        SquareLight& square = environment_squares_[l];
        square.direction = glm::normalize(rotation * rsl.center);
        square.half_edge = square_half_edge_for_rsl(rsl.half_diagonal);
        square.solid_angle = rsl.solid_angle();
        square.integral = rsl.radiance * square.solid_angle;
    }
    for (size_t i = 0; i < scene_.lights.size(); ++i) light_positions_[i] = scene_.lights[i].position_at(t);
    camera_ = scene_.camera.position_at(t);
    update_occluder_lists();
}

void Renderer::update_occluder_lists() {
    for (size_t p = 0; p < poses_.size(); ++p) {
        culling_parts_[p].transform = poses_[p].transform;
        culling_parts_[p].world_bounds = poses_[p].world_bounds;
    }
    rsl::update_occluder_lists(culling_parts_, CullingLights{environment_squares_, light_positions_, scene_.lights},
                               options_, occluder_lists_);
    stats_.occluder_pairs = occluder_lists_.pairs;
    stats_.occluder_pairs_culled = occluder_lists_.culled;
}

VertexColors Renderer::make_output() const {
    VertexColors colors;
    colors.scene_name = scene_.name;
    colors.producer = "rsl-cpu";
    for (const Part& part : scene_.parts) colors.add_part(part.name, part.mesh.vertex_count());
    return colors;
}

void Renderer::shade(VertexColors& out) {
    RSL_CHECK_EQ(out.parts.size(), scene_.parts.size());
    for (size_t p = 0; p < scene_.parts.size(); ++p) RSL_CHECK_EQ(out.parts[p].size(), scene_.parts[p].mesh.vertex_count());
    out.time = time_;
    std::atomic<size_t> lookups{0}, vertices{0}, occluder_lookups{0}, block_culled{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks_.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
        RenderStats counts;
        for (size_t b = range.begin(); b != range.end(); ++b) shade_block(blocks_[b], out, counts);
        lookups.fetch_add(counts.lookups, std::memory_order_relaxed);
        vertices.fetch_add(counts.vertices, std::memory_order_relaxed);
        occluder_lookups.fetch_add(counts.occluder_lookups, std::memory_order_relaxed);
        block_culled.fetch_add(counts.block_occluders_culled, std::memory_order_relaxed);
    });
    stats_.occluder_lookups = occluder_lookups.load();
    stats_.block_occluders_culled = block_culled.load();
    stats_.lookups = lookups.load();
    stats_.vertices = vertices.load();
    stats_.lights = rsls_.lights.size() + scene_.lights.size();
}

}  // namespace rsl
