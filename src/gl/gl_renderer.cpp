#include "src/gl/gl_renderer.h"
#include "src/gl/gl_renderer_units.h"

#include <algorithm>
#include <chrono>

#include "src/brdf/material_library.h"
#include "src/core/error.h"
#include "src/lightfit/irradiance.h"
#include "src/render/occluder_shape.h"
#include "src/render/ovdf_occluder.h"
#include "src/core/sphere_light.h"

namespace rsl::gl {

namespace {

// Mesa's software rasterizers run a pass on their own threads after the
// commands were queued, and their GL_TIME_ELAPSED queries do not span that
// work: llvmpipe 15 reads 0 ms in the viewer, and 32 ms for a pass that
// takes 1.9 s to finish. Their passes are timed by the clock instead.
bool timer_queries_measure_nothing() {
    const GLubyte* name = glGetString(GL_RENDERER);
    const std::string renderer = name ? reinterpret_cast<const char*>(name) : "";
    for (const char* software : {"llvmpipe", "softpipe", "SwiftShader"})
        if (renderer.find(software) != std::string::npos) return true;
    return false;
}

double clock_ms() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

size_t texel_bytes(const ArrayTexture& array, size_t bytes_per_texel) {
    return size_t(array.width) * array.height * bytes_per_texel;
}

}  // namespace

GlRenderer::GlRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                       const RenderOptions& options)
    : VertexRenderer(scene, std::move(environment_lights), std::move(fields), options) {
    require_gl_version(4, 3, "the GL renderer");
    const PackedGeometry geometry = pack_geometry(scene, fields_, options_.exact_shapes);
    // SVDF_STRIDE, OVDF_STRIDE: a row's texels when every field shares them, else 0 (shading_data.glsl).
    vertex_pass_defines_ = fmt::format("#define MAX_STRIDE {}\n#define SVDF_STRIDE {}\n#define OVDF_STRIDE {}\n",
                                       geometry.max_stride, std::max(geometry.svdf_stride, 0),
                                       std::max(geometry.ovdf_stride, 0));
    face_normal_.assign(geometry.face_normal.begin(), geometry.face_normal.end());
    face_s_.assign(geometry.face_s.begin(), geometry.face_s.end());
    face_t_.assign(geometry.face_t.begin(), geometry.face_t.end());
    display_program_ = build_program("display.vert.glsl", "display.frag.glsl", srgb_prelude());
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const Part& part = scene_.parts[p];
        rectangle_parts_.push_back(find_rectangle(part.mesh) ? 1 : 0);
        part_bounds_.push_back(part.mesh.bounds());
        const OccluderField* field = p < fields_.occluder.size() ? fields_.occluder[p].get() : nullptr;
        local_reach_.push_back(field ? field->reach() : BoundingSphere{});
        const Ovdf* split = split_lookup_field(field, options_.fast_occluder_lookups);
        split_fields_.push_back(split ? BoundingSphere{split->center, split->radius} : BoundingSphere{});
    }
    upload_geometry(geometry);
    upload_all_tables();
    for (auto& frame : queries_)
        for (Query& query : frame) query = make_query();
    clock_timing_ = timer_queries_measure_nothing();
    timings_.clock = clock_timing_;
    check_shadow_map_options(options_.shadow_maps);
    check_gpu_ray_options(options_.gpu_rays);
    if (options_.gpu_rays.enabled && options_.shadow_maps.enabled)
        throw_error("GL renderer: shadow maps and GPU rays are two visibility baselines; enable one");
    if (options_.gpu_rays.enabled && has_skinned_parts(scene_))
        throw_error("GL renderer: GPU rays trace rigid parts only; the scene has skinned parts (docs/design/SKINNING.md)");
    check_gl("creating the GL renderer");
    start();
}

void GlRenderer::set_sampler_units(const Program& program) {
    glUseProgram(program.id());
    for (const Sampler& sampler : kShadingSamplers) glUniform1i(uniform(program, sampler.name), sampler.unit);
    glUniform3fv(uniform(program, "u_face_normal"), 6, &face_normal_[0].x);
    glUniform3fv(uniform(program, "u_face_s"), 6, &face_s_[0].x);
    glUniform3fv(uniform(program, "u_face_t"), 6, &face_t_[0].x);
}

std::string GlRenderer::variant_defines(const VertexPassVariant& variant, bool record) const {
    return vertex_pass_defines_ +
           fmt::format("#define LIGHT_WORDS {}\n#define LAYERED {}\n#define RECORD_BLOCK_LIGHTS {}\n"
                       "#define RAY_TRACED {}\n#define SHADOW_MAPPED {}\n#define LOCAL_LIGHTS {}\n#define MAX_SLICES {}\n",
                       variant.light_words, variant.layered ? 1 : 0, record ? 1 : 0, variant.rays ? 1 : 0,
                       variant.shadow_maps ? 1 : 0, variant.local_lights ? 1 : 0, variant.slices);
}

Program GlRenderer::make_vertex_pass(const VertexPassVariant& variant, bool record) {
    const std::string defines = variant_defines(variant, record) +
                                fmt::format("#define SHADE_BLOCK {}\n#define SELF_CORNERS 1\n", kShadeBlock) +
                                shading_prelude() + shading_inputs_prelude() +
                                (variant.rays ? RayTracedVisibility::shader_text() : "") +
                                included_shader(kSourcePointSum);
    Program program = build_compute_program("shade_blocks.comp.glsl", defines);
    set_sampler_units(program);
    return program;
}

Program GlRenderer::make_pixel_pass(VertexPassVariant variant) {
    variant.rays = false;  // the ray-traced baseline draws no part per pixel (per_pixel_part)
    const std::string common = variant_defines(variant, false) + shading_prelude() + shading_inputs_prelude();
    Program program = build_program("shade_pixels.vert.glsl", "shade_pixels.frag.glsl", common + srgb_prelude(),
                                    common + included_shader(kSourcePointSum) + srgb_prelude());
    set_sampler_units(program);
    return program;
}

GlRenderer::VertexPassVariant GlRenderer::frame_vertex_pass_variant() const {
    VertexPassVariant variant;
    variant.light_words = std::max<size_t>(frame_.occluder_lists().light_words, 1);
    variant.layered = layered_;
    variant.rays = options_.gpu_rays.enabled;
    variant.shadow_maps = options_.shadow_maps.enabled;
    variant.local_lights = !frame_.light_positions().empty();
    variant.slices = 1;
    for (const auto& table : part_tables_)
        if (table) variant.slices = std::max(variant.slices, !table->isotropic() ? 4 : table->view_independent() ? 1 : 2);
    return variant;
}

GlRenderer::~GlRenderer() = default;

void GlRenderer::upload_geometry(const PackedGeometry& g) {
    vertex_count_ = int(g.positions.size());
    first_vertex_ = g.first_vertex;
    part_records_ = g.part_static;
    rect_height_ = std::max(1, (vertex_count_ + kArrayTextureWidth - 1) / kArrayTextureWidth);

    positions_ = make_array_texture(g.positions);
    normals_ = make_array_texture(g.normals);
    tangents_ = make_array_texture(g.tangents);
    skinned_ = has_skinned_parts(scene_);
    if (skinned_) packed_positions_ = g.positions, packed_normals_ = g.normals, packed_tangents_ = g.tangents;
    gpu_bytes_ = 3 * size_t(kArrayTextureWidth) * rect_height_ * 16;
    // Tables whose every value is a half (the fields store them so) lose
    // nothing in RGBA16F and halve the memory and bandwidth.
    svdf_tables_ = make_array_texture(g.svdf_tables, g.svdf_tables_half ? GL_RGBA16F : GL_RGBA32F);
    svdf_coefficients_ = make_array_texture(g.svdf_coefficients);
    ovdf_tables_ = make_array_texture(g.ovdf_tables, g.ovdf_tables_half ? GL_RGBA16F : GL_RGBA32F);
    ovdf_coefficients_ = make_array_texture(g.ovdf_coefficients);
    ovdf_frames_ = make_array_texture(g.ovdf_frames);
    gpu_bytes_ += texel_bytes(svdf_tables_, g.svdf_tables_half ? 8 : 16) + texel_bytes(svdf_coefficients_, 16) +
                  texel_bytes(ovdf_tables_, g.ovdf_tables_half ? 8 : 16) + texel_bytes(ovdf_coefficients_, 16) +
                  texel_bytes(ovdf_frames_, 16);
    parts_ = make_array_texture(part_records_);
    lights_ = make_array_texture({Vec4(0.0f)});

    // The vertex-colour buffer (both layers) and the vertex pass's blocks.
    layer_bytes_ = size_t(kArrayTextureWidth) * rect_height_ * 16;
    colors_ = make_buffer();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, colors_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(2 * layer_bytes_), nullptr, GL_DYNAMIC_COPY);
    const PackedBlocks blocks = pack_blocks(scene_, g.first_vertex);
    block_count_ = int(blocks.blocks.size());
    for (const glm::ivec4& block : blocks.blocks) block_parts_.push_back(block.x);
    blocks_ = make_buffer();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, blocks_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(blocks.blocks.size(), 1) * sizeof(glm::ivec4)),
                 blocks.blocks.empty() ? nullptr : blocks.blocks.data(), GL_STATIC_DRAW);
    block_vertices_ = make_buffer();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, block_vertices_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(blocks.vertices.size(), 1) * sizeof(int32_t)),
                 blocks.vertices.empty() ? nullptr : blocks.vertices.data(), GL_STATIC_DRAW);
    candidates_ = make_buffer();
    part_culling_ = make_buffer();
    counters_ = make_buffer();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, counters_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(kCounterCount * sizeof(uint32_t)), nullptr, GL_DYNAMIC_READ);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gpu_bytes_ += 2 * layer_bytes_ + blocks.blocks.size() * sizeof(glm::ivec4) + blocks.vertices.size() * sizeof(int32_t);

    // Display geometry: part-space positions of every vertex, indices per part.
    std::vector<Vec3> positions3;
    std::vector<Vec2> texcoords;  // 0 for parts without: only textured parts read them
    std::vector<uint32_t> indices;
    first_index_.clear();
    display_first_vertex_.clear();
    for (const Part& part : scene_.parts) {
        display_first_vertex_.push_back(positions3.size());
        positions3.insert(positions3.end(), part.mesh.positions.begin(), part.mesh.positions.end());
        if (part.mesh.texcoords.size() == part.mesh.vertex_count())
            texcoords.insert(texcoords.end(), part.mesh.texcoords.begin(), part.mesh.texcoords.end());
        else
            texcoords.resize(positions3.size(), Vec2(0.0f));
        first_index_.push_back(indices.size());
        indices.insert(indices.end(), part.mesh.indices.begin(), part.mesh.indices.end());
    }
    first_index_.push_back(indices.size());
    empty_vao_ = make_vertex_array();
    display_vao_ = make_vertex_array();
    glBindVertexArray(display_vao_.id());
    display_positions_ = make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, display_positions_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions3.size() * sizeof(Vec3)), positions3.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, colors_.id());
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 16, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 16, reinterpret_cast<const void*>(layer_bytes_));
    glEnableVertexAttribArray(2);
    display_texcoords_ = make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, display_texcoords_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(texcoords.size() * sizeof(Vec2)), texcoords.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, sizeof(Vec2), nullptr);
    glEnableVertexAttribArray(3);
    upload_uint_array(indices_, indices);  // the per-pixel pass's corners (gl_PrimitiveID)
    display_indices_ = make_buffer();
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, display_indices_.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(),
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    gpu_bytes_ += positions3.size() * (sizeof(Vec3) + sizeof(Vec2)) + indices.size() * sizeof(uint32_t) +
                  texel_bytes(indices_, 4);
    check_gl("uploading the scene");
}

void GlRenderer::set_toggles(const RenderOptions& options) {
    options_.environment = options.environment;
    options_.local_lights = options.local_lights;
    options_.self_visibility = options.self_visibility;
    options_.occluders = options.occluders;
    options_.occluder_culling = options.occluder_culling;
    check_shadow_map_options(options.shadow_maps);
    options_.shadow_maps = options.shadow_maps;
    check_gpu_ray_options(options.gpu_rays);
    if (options.gpu_rays.enabled && has_skinned_parts(scene_))
        throw_error("GL renderer: GPU rays trace rigid parts only; the scene has skinned parts (docs/design/SKINNING.md)");
    options_.gpu_rays = options.gpu_rays;
    options_.pixel_shadows = options.pixel_shadows;
    options_.pixel_highlights = options.pixel_highlights;
    shadow_maps_stale_ = true;
}

void GlRenderer::frame_changed() {
    shadow_maps_stale_ = true;  // poses or lights may have moved
    shaded_current_frame_ = false;
    pack_block_candidates(frame_.occluder_lists(), candidate_words_);
    pack_part_culling(frame_.poses(), local_reach_, split_fields_, part_culling_records_);
    stats_.lights = frame_.environment_squares().size() + frame_.light_positions().size();
    stats_.vertices = size_t(vertex_count_);
}

// The frame's skinned vertices (FrameSetup::skinned, the CPU renderer's very
// numbers) into the vertex texels and the display positions: the part's
// rigid pose then places them as any part's.
void GlRenderer::upload_skinned_vertices() {
    if (!skinned_) return;
    glBindBuffer(GL_ARRAY_BUFFER, display_positions_.id());
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const PosedVertices* posed = frame_.skinned(p);
        if (!posed) continue;
        const size_t first = size_t(first_vertex_[p]);
        for (size_t v = 0; v < posed->positions.size(); ++v) {
            packed_positions_[first + v] = Vec4(posed->positions[v], packed_positions_[first + v].w);
            packed_normals_[first + v] = Vec4(posed->normals[v], packed_normals_[first + v].w);
            if (!posed->tangents.empty())
                packed_tangents_[first + v] = Vec4(Vec3(posed->tangents[v]), packed_tangents_[first + v].w);
        }
        glBufferSubData(GL_ARRAY_BUFFER, GLintptr(display_first_vertex_[p] * sizeof(Vec3)),
                        GLsizeiptr(posed->positions.size() * sizeof(Vec3)), posed->positions.data());
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    update_array_texture(positions_, packed_positions_);
    update_array_texture(normals_, packed_normals_);
    update_array_texture(tangents_, packed_tangents_);
}

// Poses into the part records; lights (2 texels each); occluder lists.
void GlRenderer::upload_frame() {
    upload_skinned_vertices();
    const auto& poses = frame_.poses();
    for (size_t p = 0; p < poses.size(); ++p)
        write_pose(poses[p].transform, poses[p].normal, poses[p].inverse, &part_records_[p * kPartStride]);
    update_array_texture(parts_, part_records_);

    light_texels_.clear();
    static_assert(kLightTexels == 3, "three texels per light below");
    for (const SquareLight& square : frame_.environment_squares()) {
        light_texels_.push_back(Vec4(square.direction, square.half_edge));
        light_texels_.push_back(Vec4(square.integral, 0.0f));
        light_texels_.push_back(Vec4(0.0f));
    }
    for (size_t i = 0; i < local_lights_.size(); ++i) {
        const Vec2 cone = spot_cone_scale_offset(local_lights_[i]);
        light_texels_.push_back(Vec4(frame_.light_positions()[i], local_lights_[i].radius));
        light_texels_.push_back(Vec4(sphere_light_radiance(local_lights_[i]), cone.x));
        light_texels_.push_back(Vec4(frame_.light_axes()[i], cone.y));
    }
    // The exact diffuse light's irradiance maps after the lights (shaders/point_sum.glsl).
    irradiance_first_ = irradiance_second_ = -1;
    if (options_.exact_diffuse_light && has_irradiance(environment_)) {
        auto append = [&](const IrradianceMap& map) {
            const int first = int(light_texels_.size());
            for (const Color& node : map.nodes) light_texels_.push_back(Vec4(node, 0.0f));
            return first;
        };
        irradiance_first_ = append(*environment_.first.irradiance);
        if (environment_.blends()) irradiance_second_ = append(*environment_.second.irradiance);
    }
    if (light_texels_.empty()) light_texels_.push_back(Vec4(0.0f));
    update_array_texture(lights_, light_texels_);

    glBindBuffer(GL_SHADER_STORAGE_BUFFER, candidates_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(candidate_words_.size() * sizeof(uint32_t)),
                 candidate_words_.data(), GL_STREAM_DRAW);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, part_culling_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(part_culling_records_.size() * sizeof(Vec4)),
                 part_culling_records_.data(), GL_STREAM_DRAW);
    const uint32_t zeros[kCounterCount] = {};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, counters_.id());
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeros), zeros);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

void GlRenderer::shade_on_device() {
    collect_timings();
    sync_materials();
    upload_frame();
    render_shadow_maps();
    if (options_.gpu_rays.enabled) {
        if (!rays_) rays_ = std::make_unique<RayTracedVisibility>(scene_, first_vertex_);
        std::vector<Mat4> transforms;
        for (const PartPose& pose : frame_.poses()) transforms.push_back(pose.transform);
        rays_->set_poses(transforms);
    }
    if (const VertexPassVariant variant = frame_vertex_pass_variant(); !vertex_pass_ || variant != vertex_pass_variant_) {
        vertex_pass_ = make_vertex_pass(variant, false);
        vertex_pass_variant_ = variant;
    }
    begin_pass(kPassShade);
    run_vertex_pass(vertex_pass_);
    end_pass(kPassShade);
    query_pending_[frame_parity_] = !clock_timing_;
    drew_[frame_parity_] = false;
    check_gl("the shading pass");
    shaded_current_frame_ = true;
}

void GlRenderer::run_vertex_pass(const Program& program) {
    glUseProgram(program.id());
    bind_shading_inputs(program);
    glUniform1i(uniform(program, "u_block_count"), block_count_);
    glUniform1i(uniform(program, "u_part_count"), int(scene_.parts.size()));
    glUniform1i(uniform(program, "u_layer_offset"), int(layer_bytes_ / 16));
    glUniform1i(uniform(program, "u_culling"), options_.occluder_culling ? 1 : 0);
    if (options_.gpu_rays.enabled) {
        rays_->bind(program);
        glUniform1i(uniform(program, "u_ray_samples"), options_.gpu_rays.samples_per_side);
    }
    const std::pair<StorageBinding, const Buffer*> buffers[] = {
        {kBindingBlocks, &blocks_},           {kBindingBlockVertices, &block_vertices_},
        {kBindingCandidates, &candidates_},   {kBindingPartCulling, &part_culling_},
        {kBindingCounters, &counters_},       {kBindingColors, &colors_}};
    for (const auto& [binding, buffer] : buffers) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer->id());
    // At most 65,535 workgroups along an axis: the blocks as rows of that many.
    const GLuint groups = GLuint(std::max(block_count_, 1));
    const GLuint columns = std::min<GLuint>(groups, 65535);
    glDispatchCompute(columns, (groups + columns - 1) / columns, 1);
    // The display pass draws the colours as vertex attributes; read_colors copies them.
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

std::vector<std::vector<uint32_t>> GlRenderer::block_candidate_lights() {
    sync_materials();
    upload_frame();
    const OccluderLists& lists = frame_.occluder_lists();
    const size_t words = std::max<size_t>(lists.light_words, 1);
    std::vector<uint32_t> offsets;
    size_t total = 0;
    for (const int part : block_parts_) {
        offsets.push_back(uint32_t(total));
        total += (lists.candidate_offsets[size_t(part) + 1] - lists.candidate_offsets[size_t(part)]) * words;
    }
    Buffer recorded = make_buffer(), record_offsets = make_buffer();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, recorded.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(total, 1) * 4), nullptr, GL_DYNAMIC_READ);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, record_offsets.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(offsets.size(), 1) * 4), offsets.data(),
                 GL_STATIC_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingRecorded, recorded.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingRecordOffsets, record_offsets.id());
    const Program program = make_vertex_pass(frame_vertex_pass_variant(), true);
    run_vertex_pass(program);
    std::vector<uint32_t> flat(std::max<size_t>(total, 1));
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, recorded.id());
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(flat.size() * 4), flat.data());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    check_gl("recording the blocks' candidate lights");
    shaded_current_frame_ = false;  // the colours are the record pass's, not a timed frame's
    std::vector<std::vector<uint32_t>> blocks;
    for (size_t b = 0; b < block_parts_.size(); ++b) {
        const size_t end = b + 1 < offsets.size() ? offsets[b + 1] : total;
        blocks.emplace_back(flat.begin() + std::ptrdiff_t(offsets[b]), flat.begin() + std::ptrdiff_t(end));
    }
    return blocks;
}

void GlRenderer::bind_shading_inputs(const Program& program) {
    bind_texture(kUnitPositions, GL_TEXTURE_2D, positions_.texture.id());
    bind_texture(kUnitNormals, GL_TEXTURE_2D, normals_.texture.id());
    bind_texture(kUnitTangents, GL_TEXTURE_2D, tangents_.texture.id());
    bind_texture(kUnitParts, GL_TEXTURE_2D, parts_.texture.id());
    bind_texture(kUnitLights, GL_TEXTURE_2D, lights_.texture.id());
    bind_texture(kUnitBrdf, GL_TEXTURE_3D, brdf_.id());
    bind_texture(kUnitBrdfOffsets, GL_TEXTURE_2D, brdf_offsets_.texture.id());
    bind_texture(kUnitSvdfTables, GL_TEXTURE_2D, svdf_tables_.texture.id());
    bind_texture(kUnitSvdfCoefficients, GL_TEXTURE_2D, svdf_coefficients_.texture.id());
    bind_texture(kUnitOvdfTables, GL_TEXTURE_2D, ovdf_tables_.texture.id());
    bind_texture(kUnitOvdfCoefficients, GL_TEXTURE_2D, ovdf_coefficients_.texture.id());
    bind_texture(kUnitOvdfFrames, GL_TEXTURE_2D, ovdf_frames_.texture.id());
    bind_texture(kUnitPbrPoints, GL_TEXTURE_2D, pbr_points_.texture.id());
    glUniform1i(uniform(program, "u_environment_lights"), int(frame_.environment_squares().size()));
    glUniform1i(uniform(program, "u_light_count"), int(stats_.lights));
    glUniform1i(uniform(program, "u_environment_enabled"), options_.environment ? 1 : 0);
    glUniform1i(uniform(program, "u_local_enabled"), options_.local_lights ? 1 : 0);
    glUniform1i(uniform(program, "u_self_visibility"), options_.self_visibility ? 1 : 0);
    glUniform1i(uniform(program, "u_brdf_resolution"), materials_.resolution);
    glUniform1i(uniform(program, "u_brdf_tiles"), brdf_tiles_);
    glUniform4fv(uniform(program, "u_pbr_basis"), kPbrBasisRecords, &pbr_basis_records_[0].x);
    const bool irradiance = irradiance_first_ >= 0;
    glUniform1i(uniform(program, "u_irradiance_resolution"), irradiance ? environment_.first.irradiance->resolution : 0);
    glUniform1i(uniform(program, "u_irradiance_first"), irradiance_first_);
    glUniform1i(uniform(program, "u_irradiance_second"), irradiance_second_);
    glUniform2f(uniform(program, "u_irradiance_weights"), frame_.blend().first, frame_.blend().second);
    glUniformMatrix3fv(uniform(program, "u_environment_rotation"), 1, GL_FALSE, &frame_.environment_rotation()[0][0]);
    const Vec3 camera = frame_.camera();
    glUniform3f(uniform(program, "u_camera"), camera.x, camera.y, camera.z);
    bind_shadow_uniforms(program);
}

void GlRenderer::render_shadow_maps() {
    shadowed_[frame_parity_] = false;
    if (clock_timing_) timings_.shadow_ms = 0;  // this frame's, unless drawn below
    const ShadowMapOptions& options = options_.shadow_maps;
    const std::vector<SquareLight>& squares = frame_.environment_squares();
    if (!options.enabled || !options_.environment || squares.empty()) return;
    if (!shadow_maps_) shadow_maps_ = std::make_unique<ShadowMaps>();
    if (!shadow_maps_stale_ && shadow_maps_->resolution() == options.resolution &&
        shadow_maps_->layers() == int(squares.size()))
        return;
    begin_pass(kPassShadow);
    shadow_maps_->render(options.resolution, frame_.poses(), squares,
                         ShadowCasters{display_vao_.id(), first_index_, first_vertex_});
    end_pass(kPassShadow);
    shadow_maps_stale_ = false;
    shadowed_[frame_parity_] = true;
}

// The shading pass's view of the maps; u_shadow_maps false leaves the RSL visibility.
void GlRenderer::bind_shadow_uniforms(const Program& program) {
    const bool on = options_.shadow_maps.enabled && shadow_maps_ && shadow_maps_->layers() > 0;
    glUniform1i(uniform(program, "u_shadow_maps"), on ? 1 : 0);
    if (on) shadow_maps_->bind_for_shading(program, options_.shadow_maps, kUnitShadowMaps);
}

void GlRenderer::begin_pass(int pass) {
    if (!clock_timing_) {
        glBeginQuery(GL_TIME_ELAPSED, queries_[frame_parity_][pass].id());
        return;
    }
    glFinish();  // earlier work is not this pass's
    pass_start_ms_ = clock_ms();
}

void GlRenderer::end_pass(int pass) {
    if (!clock_timing_) {
        glEndQuery(GL_TIME_ELAPSED);
        return;
    }
    glFinish();
    double* ms[kPassCount] = {&timings_.shade_ms, &timings_.display_ms, &timings_.shadow_ms};
    *ms[pass] = clock_ms() - pass_start_ms_;
}

// Reads the previous use of this parity's queries, if they are done (never waits).
void GlRenderer::collect_timings() {
    frame_parity_ ^= 1;
    if (!query_pending_[frame_parity_]) return;
    Query* queries = queries_[frame_parity_];
    GLuint available = 0;
    glGetQueryObjectuiv(queries[kPassShade].id(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) return;
    GLuint64 ns[kPassCount] = {0, 0, 0};
    const bool ran[kPassCount] = {true, drew_[frame_parity_], shadowed_[frame_parity_]};
    for (int q = 0; q < kPassCount; ++q) {
        if (!ran[q]) continue;
        glGetQueryObjectuiv(queries[q].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available) glGetQueryObjectui64v(queries[q].id(), GL_QUERY_RESULT, &ns[q]);
    }
    timings_.shade_ms = double(ns[kPassShade]) * 1e-6;
    timings_.display_ms = double(ns[kPassDisplay]) * 1e-6;
    timings_.shadow_ms = double(ns[kPassShadow]) * 1e-6;
    query_pending_[frame_parity_] = false;
}

std::string GlRenderer::pass_times() const {
    const PassTimings& t = timings_;
    const std::string shadow = t.shadow_ms > 0 ? fmt::format("shadow maps {:.1f} ms, ", t.shadow_ms) : "";
    return fmt::format("{}shading {:.1f} ms{}", shadow, t.shade_ms, t.clock ? " (clock)" : " (timer queries)");
}

void GlRenderer::shade(VertexColors& out) {
    shade_on_device();
    read_colors(out);
    const DeviceCounts counts = device_counts();
    stats_.occluder_lookups = counts.occluder_lookups;
    stats_.block_occluders_culled = counts.block_pairs_culled;
    stats_.shadow_rays = counts.shadow_rays;
}

DeviceCounts GlRenderer::device_counts() const {
    uint32_t words[kCounterCount] = {};
    glBindBuffer(GL_COPY_READ_BUFFER, counters_.id());
    glGetBufferSubData(GL_COPY_READ_BUFFER, 0, sizeof(words), words);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    check_gl("reading the vertex pass's counters");
    DeviceCounts counts;
    counts.occluder_lookups = words[kCounterOccluderLookups];
    counts.block_pairs = words[kCounterBlockPairs];
    counts.block_pairs_culled = words[kCounterBlockPairsCulled];
    counts.shadow_rays = words[kCounterShadowRays];
    return counts;
}

void GlRenderer::read_colors(VertexColors& out) const {
    RSL_CHECK_EQ(out.parts.size(), scene_.parts.size());
    // Any `out` (the viewer's too) gets the layers of the shaded materials;
    // a textured part without texture coordinates is refused here.
    match_layers(library_, scene_, out);
    const size_t parts = scene_.parts.size();
    // Layer 0 at the buffer's start, the specular layer one vertex rectangle further.
    std::vector<Vec4> texels(static_cast<size_t>(vertex_count_) * (layered_ ? 2 : 1));
    glBindBuffer(GL_COPY_READ_BUFFER, colors_.id());
    glGetBufferSubData(GL_COPY_READ_BUFFER, 0, GLsizeiptr(size_t(vertex_count_) * sizeof(Vec4)), texels.data());
    if (layered_)
        glGetBufferSubData(GL_COPY_READ_BUFFER, GLintptr(layer_bytes_), GLsizeiptr(size_t(vertex_count_) * sizeof(Vec4)),
                           texels.data() + vertex_count_);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    check_gl("reading the vertex colours");
    out.time = time_;
    for (size_t p = 0; p < parts; ++p) {
        RSL_CHECK_EQ(out.parts[p].size(), scene_.parts[p].mesh.vertex_count());
        for (size_t v = 0; v < out.parts[p].size(); ++v) out.parts[p][v] = Color(texels[first_vertex_[p] + v]);
        // match_layers gave `out` the layers of the library's materials, which the tables follow.
        RSL_CHECK_EQ(out.layered(p), part_tables_[parts + p] != nullptr);
        if (!out.layered(p)) continue;
        for (size_t v = 0; v < out.specular[p].size(); ++v)
            out.specular[p][v] = Color(texels[size_t(vertex_count_ + first_vertex_[p]) + v]);
    }
    // The device's colours hold no emission: the display pass adds it per pixel.
    add_emission(library_, scene_, out);
}

}  // namespace rsl::gl
