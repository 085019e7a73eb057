// Set-up and per-frame state of the CPU renderer; the per-block shading kernel
// is in shade_block.cpp.
#include "src/render/cpu_renderer.h"

#include <atomic>

#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "src/core/skinning.h"
#include "src/render/occluder_shape.h"
#include "src/render/ovdf_occluder.h"
#include "src/core/sphere_light.h"
#include "src/render/block_scratch.h"
#include "src/formats/scene_environment.h"
#include "src/render/vertex_blocks.h"

namespace rsl {

CpuRenderer::CpuRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                         const RenderOptions& options)
    : VertexRenderer(scene, std::move(environment_lights), std::move(fields), options) {
    // A GL baseline (docs/design/GPU_DESIGN.md "Shadow-mapped visibility"): there is no CPU version to fall back on.
    if (options.shadow_maps.enabled)
        throw_file_error(scene.source, "shadow-mapped visibility (RenderOptions::shadow_maps, --shadow-maps) "
                                       "exists on the GL backend only; the CPU renderer has none");
    if (options.gpu_rays.enabled)
        throw_file_error(scene.source, "GPU ray-traced visibility (RenderOptions::gpu_rays, --gpu-rays) exists on "
                                       "the GL backend only; on the CPU, RenderOptions::exact_visibility traces the same rays");
    const size_t parts = scene.parts.size();
    seam_partners_ = seam_partners(scene);
    for (size_t p = 0; p < parts; ++p) {
        const Part& part = scene.parts[p];
        const size_t n = part.mesh.vertex_count();
        if (part.mesh.normals.size() != n)
            throw_file_error(scene.source, "part '{}' has {} normals for {} vertices", part.name,
                             part.mesh.normals.size(), n);
        block_order_.push_back(spatial_block_order(part.mesh.positions, kShadeBlock));
        local_bounds_.push_back(part.mesh.bounding_sphere());
        local_boxes_.push_back(part.mesh.bounds());
        shapes_.push_back(options_.exact_shapes ? find_occluder_shape(part.mesh) : OccluderShape{});
        local_reach_.push_back(fields_.occluder[p] ? fields_.occluder[p]->reach() : BoundingSphere{});
        const Ovdf* split = split_lookup_field(fields_.occluder[p].get(), options_.fast_occluder_lookups);
        fast_lookups_.push_back(split ? std::make_unique<const OvdfLookup>(*split) : nullptr);
        // Per pixel only with the fields' occluder factor (not the
        // ray-traced diagnostics), and only where there is one.
        const bool per_pixel = options_.occluders && !options_.exact_visibility &&
                               (options_.pixel_shadows == PixelShadows::All ||
                                (options_.pixel_shadows == PixelShadows::Planes && find_rectangle(part.mesh)));
        pixel_parts_.push_back(per_pixel ? 1 : 0);
    }
    blocks_ = vertex_blocks(block_order_);
    pixel_terms_.resize(parts);
    rim_view_floor_.resize(parts);
    enclosed_vertices_.resize(parts);
    part_tables_.assign(parts, nullptr);
    part_specular_tables_.assign(parts, nullptr);
    part_constant_terms_.assign(parts, Color(0));
    part_pbr_points_.assign(parts, {});
    part_pbr_base_.assign(parts, Color(0));
    synced_material_.assign(parts, -1);
    sync_materials();
    start();
}

void CpuRenderer::lights_changed() {
    light_radiance_.clear();
    light_cones_.clear();
    for (const LocalLight& light : local_lights_) {
        light_radiance_.push_back(sphere_light_radiance(light));
        light_cones_.push_back(spot_cone_scale_offset(light));
    }
}

// The library builds a table when a material is edited; here the parts only
// pick up the pointers of what changed (no allocation, O(parts)).
void CpuRenderer::sync_materials() {
    const int materials = library_.material_count();
    if (synced_revision_.size() != size_t(materials)) synced_revision_.assign(size_t(materials), 0);
    for (size_t p = 0; p < part_tables_.size(); ++p) {
        const int m = library_.part_material(int(p));
        if (m != synced_material_[p] || library_.revision(m) != synced_revision_[size_t(m)] || !part_tables_[p]) {
            part_tables_[p] = &library_.part_table(int(p));
            part_specular_tables_[p] = library_.part_specular_table(int(p));
            part_constant_terms_[p] = library_.brdf(m).constant_part();
            const MaterialDesc& desc = library_.desc(m);
            part_pbr_points_[p] = varies_per_point(desc) ? pbr_points(desc, scene_.parts[p].mesh) : std::vector<PbrPoint>{};
            part_pbr_base_[p] = varies_per_point(desc) ? pbr_base_color(desc) : Color(0);
            synced_material_[p] = m;
        }
    }
    for (int m = 0; m < materials; ++m) synced_revision_[size_t(m)] = library_.revision(m);
}

void CpuRenderer::shade(VertexColors& out) {
    RSL_CHECK_EQ(out.parts.size(), scene_.parts.size());
    for (size_t p = 0; p < scene_.parts.size(); ++p) RSL_CHECK_EQ(out.parts[p].size(), scene_.parts[p].mesh.vertex_count());
    sync_materials();
    match_layers(library_, scene_, out);
    out.time = time_;
    shaded_current_frame_ = true;
    terms_kept_ = keep_image_terms_;
    // The terms image formation takes per pixel (pixel_shading.cpp), sized
    // once (again when the light count or a part's material changes).
    const size_t lights = environment_squares_.size() + light_positions_.size();
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const bool glossy = library_.desc(library_.part_material(int(p))).model != "lambert";
        const bool highlights = keep_image_terms_ && options_.pixel_highlights && !options_.exact_visibility &&
                                glossy && !part_specular_tables_[p] && lights <= size_t(kShadeBlock);
        const bool shadows = keep_image_terms_ && pixel_parts_[p];
        const size_t terms = scene_.parts[p].mesh.vertex_count() * lights;
        PixelTerms& t = pixel_terms_[p];
        t.unshadowed.resize(shadows ? terms : 0);
        t.unshadowed_specular.resize(shadows && part_specular_tables_[p] ? terms : 0);
        t.occlusion.resize(shadows || highlights ? terms : 0);
        t.self_visibility.resize(highlights ? terms : 0);
        if (highlights && rim_view_floor_[p].empty()) rim_view_floor_[p] = rim_view_floors(scene_.parts[p].mesh);
        const Svdf* svdf = options_.self_visibility && p < fields_.self.size() ? fields_.self[p].get() : nullptr;
        if (highlights && svdf && enclosed_vertices_[p].empty()) enclosed_vertices_[p] = svdf->enclosed_vertices();
        if (!svdf) enclosed_vertices_[p].clear();
    }
    std::atomic<size_t> lookups{0}, vertices{0}, occluder_lookups{0}, block_culled{0}, shadow_rays{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks_.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
        RenderStats counts;
        for (size_t b = range.begin(); b != range.end(); ++b) shade_block(blocks_[b], out, counts);
        lookups.fetch_add(counts.lookups, std::memory_order_relaxed);
        vertices.fetch_add(counts.vertices, std::memory_order_relaxed);
        occluder_lookups.fetch_add(counts.occluder_lookups, std::memory_order_relaxed);
        block_culled.fetch_add(counts.block_occluders_culled, std::memory_order_relaxed);
        shadow_rays.fetch_add(counts.shadow_rays, std::memory_order_relaxed);
    });
    stats_.shadow_rays = shadow_rays.load();
    stats_.occluder_lookups = occluder_lookups.load();
    stats_.block_occluders_culled = block_culled.load();
    stats_.lookups = lookups.load();
    stats_.vertices = vertices.load();
    stats_.lights = environment_squares_.size() + local_lights_.size();
    add_emission(library_, scene_, out);
}

}  // namespace rsl
