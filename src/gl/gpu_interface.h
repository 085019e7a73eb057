#pragma once
// The GL renderer's interface between host and shaders, declared once
// (docs/design/GPU_DESIGN.md "The shading core"): storage-buffer bindings,
// texture units with their samplers, and the GLSL files the host puts before
// a pass's own text, in their order. The host binds by these constants; the
// shaders get them from shader_interface_glsl() (macros: GLSL 4.30 wants a
// binding as a literal) and shader_sampler_declarations(), so that neither
// side writes a binding, a unit or a source-string number by hand. Built
// without any GL call, so that the table can be tested by itself
// (tests/gl/gpu_layout_test.cpp).
#include <cstddef>
#include <iterator>
#include <string>

namespace rsl::gl {

// Storage-buffer bindings. The vertex pass's (and the per-pixel pass's
// candidates and culling) come first, then the GPU rays'; a compute pass
// that runs alone (the BVH refit, the ray test) reuses the low ones.
enum StorageBinding : int {
    kBindingBlocks = 0,          // shade_blocks.comp.glsl: per block (part, first entry, count, 0)
    kBindingBlockVertices = 1,   // per block entry: the vertex's index in the vertex rectangle
    kBindingCandidates = 2,      // point_sum.glsl: the frame's candidates (pack_block_candidates)
    kBindingPartCulling = 3,     // per part kCullingStride vec4 (pack_part_culling)
    kBindingCounters = 4,        // kCounter* (GlRenderer::device_counts)
    kBindingColors = 5,          // per vertex its colour (then the specular layer)
    kBindingRecorded = 6,        // GlRenderer::block_candidate_lights (tests only)
    kBindingRecordOffsets = 7,
    kBindingBvhNodes = 8,        // bvh_traverse.glsl (src/gl/gpu_bvh.h)
    kBindingBvhTriangles = 9,
    kBindingBvhInstances = 10,
    kBindingRayInward = 12,      // ray_visibility.glsl: per vertex its border's inward direction
    kBindingBvhLevels = 0,       // bvh_refit.comp.glsl: the top nodes, deepest level first
    kBindingRays = 0,            // trace_rays.comp.glsl: per ray (origin, direction)
    kBindingHits = 1,            // per ray whether it is blocked
};

// A constant as the shaders see it: its GLSL name and value.
struct GlslConstant {
    const char* name;
    int value;
};

// Every binding, by the macro the shaders use in their layouts.
inline constexpr GlslConstant kStorageBindings[] = {
    {"BLOCKS_BINDING", kBindingBlocks},
    {"BLOCK_VERTICES_BINDING", kBindingBlockVertices},
    {"CANDIDATES_BINDING", kBindingCandidates},
    {"PART_CULLING_BINDING", kBindingPartCulling},
    {"COUNTERS_BINDING", kBindingCounters},
    {"COLORS_BINDING", kBindingColors},
    {"RECORDED_BINDING", kBindingRecorded},
    {"RECORD_OFFSETS_BINDING", kBindingRecordOffsets},
    {"BVH_NODES_BINDING", kBindingBvhNodes},
    {"BVH_TRIANGLES_BINDING", kBindingBvhTriangles},
    {"BVH_INSTANCES_BINDING", kBindingBvhInstances},
    {"RAY_INWARD_BINDING", kBindingRayInward},
    {"BVH_LEVELS_BINDING", kBindingBvhLevels},
    {"RAYS_BINDING", kBindingRays},
    {"HITS_BINDING", kBindingHits},
};

// Texture units of the shading inputs (the vertex pass and the per-pixel
// pass bind the same), then the per-pixel pass's base colour texture,
// triangle indices and emissive texture; the display and skybox passes, programs of their own,
// use the first units again.
enum Unit : int {
    kUnitPositions, kUnitNormals, kUnitTangents, kUnitParts, kUnitLights, kUnitBrdf,
    kUnitBrdfOffsets, kUnitSvdfTables, kUnitSvdfCoefficients, kUnitOvdfTables, kUnitOvdfCoefficients,
    kUnitOvdfFrames, kUnitShadowMaps, kUnitBaseColor, kUnitIndices, kUnitPbrPoints, kUnitMetallicRoughness,
    kUnitEmissive, kUnitCount,
    // A unit no pass reads: where a texture is made and filled without
    // replacing one a pass has bound.
    kUnitUpload = kUnitCount,
    kUnitDisplayBaseColor = 0,  // display.frag.glsl's u_base_color
    kUnitDisplayEmissive = 1,   // display.frag.glsl's u_emissive_texture
    kUnitSkyFirst = 0,          // skybox.frag.glsl's u_first and u_second
    kUnitSkySecond = 1,
};

// The shading passes' samplers, one per unit in unit order: the GLSL
// declaration (shader_sampler_declarations) and the unit the host sets it to
// (GlRenderer::set_sampler_units) come from the same row.
struct Sampler {
    int unit;
    const char* type;
    const char* name;
    const char* comment;
};
inline constexpr Sampler kShadingSamplers[] = {
    {kUnitPositions, "sampler2D", "u_positions", "vertex rectangle: part-space position, part"},
    {kUnitNormals, "sampler2D", "u_normals", "normal, SVDF cluster"},
    {kUnitTangents, "sampler2D", "u_tangents", "tangent"},
    {kUnitParts, "sampler2D", "u_parts", "part records (kPartStride texels each)"},
    {kUnitLights, "sampler2D", "u_lights", "kLightTexels per light"},
    {kUnitBrdf, "sampler3D", "u_brdf", "per slice: rows of corner sums, then texels (append_texture_rows)"},
    {kUnitBrdfOffsets, "sampler2D", "u_brdf_offsets", "per slice mean offset"},
    {kUnitSvdfTables, "sampler2D", "u_svdf_tables", "SVDF tables"},
    {kUnitSvdfCoefficients, "sampler2D", "u_svdf_coefficients", "SVDF coefficients"},
    {kUnitOvdfTables, "sampler2D", "u_ovdf_tables", "OVDF tables"},
    {kUnitOvdfCoefficients, "sampler2D", "u_ovdf_coefficients", "OVDF coefficients"},
    {kUnitOvdfFrames, "sampler2D", "u_ovdf_frames", "OVDF sample frames, zoom records, surfaces, spans"},
    {kUnitShadowMaps, "sampler2DArray", "u_shadow_depths", "the shadow maps, layer l = environment light l"},
    {kUnitBaseColor, "sampler2D", "u_base_color", "the per-pixel pass's base colour texture"},
    {kUnitIndices, "usampler2D", "u_indices", "every part's triangle indices (part-local vertices)"},
    {kUnitPbrPoints, "sampler2D", "u_pbr_points", "vertex rectangle: (roughness, metallic) where the material varies per point"},
    {kUnitMetallicRoughness, "sampler2D", "u_metallic_roughness", "the per-pixel pass's metallic-roughness texture"},
    {kUnitEmissive, "sampler2D", "u_emissive_texture", "the per-pixel pass's emissive texture"},
};
static_assert(std::size(kShadingSamplers) == kUnitCount);

// The GLSL files the host puts before a pass's own text (source string 0),
// in the order they go in; each one's source-string number (`#line 1 N`,
// so that a driver's message names its file) is its place in this list.
enum ShaderSource : int {
    kSourcePass,               // the pass's own file
    kSourceShadingCore,        // src/shading/shading_core.h's GLSL part (embedded as shading_core.glsl)
    kSourceShadingData,        // shading_data.glsl: what the sum reads
    kSourceVisibilityFields,   // visibility_fields.glsl: SVDF, OVDF, exact shapes
    kSourceShadowMapFilter,    // shadow_map_filter.glsl: the shadow-map baseline
    kSourceBvhTraverse,        // bvh_traverse.glsl: the GPU rays (RAY_TRACED)
    kSourceRayVisibility,      // ray_visibility.glsl
    kSourcePointSum,           // point_sum.glsl: the sum itself
    kSourceSrgb,               // srgb.glsl: the display's curve
    kSourceCount,
};
inline constexpr const char* kShaderSourceFiles[kSourceCount] = {
    nullptr,                  "shading_core.glsl",   "shading_data.glsl",
    "visibility_fields.glsl", "shadow_map_filter.glsl", "bvh_traverse.glsl",
    "ray_visibility.glsl",    "point_sum.glsl",      "srgb.glsl",
};

// `#define NAME value` of every storage binding, one a line.
std::string shader_interface_glsl();
// The shading passes' sampler declarations (kShadingSamplers), one a line.
std::string shader_sampler_declarations();

}  // namespace rsl::gl
