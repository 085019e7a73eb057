#pragma once
// How the GPU renderer lays its data out in textures (docs/design/GPU_DESIGN.md), built on
// the CPU without any GL call so that the layout can be tested by itself.
//
// Flat arrays go into RGBA "array textures" (gl_objects.h): element i at texel
// (i % 2048, i / 2048). Indices stored in float texels are exact: below 2^24
// (checked), and block starts beyond it by alignment (block_start).
//
//  vertex rectangle (3 textures, one texel per vertex, vertex i at (i % W, i / W)):
//    positions  xyz = part-space position, w = part index
//    normals    xyz = part-space normal,   w = SVDF cluster of the vertex (−1: none)
//    tangents   xyz = part-space tangent (0: none)
//  parts (kPartStride texels per part): pose, material, SVDF and OVDF records, exact shape
//  lights (kLightTexels per light): environment square (direction, half-edge), (integral, 0), unused;
//    sphere light (position, radius), (radiance, spot cone scale), (spot axis, spot cone offset)
//  SVDF / OVDF tables: per (cluster, texel) `stride` texels = [μ, b₀ … b_{k−1}] padded
//  SVDF / OVDF coefficients: per vertex / sample `stride` texels = [1, w₀ … w_{k−1}] padded,
//    so a reconstruction is Σ_t dot(table_t, coefficients_t)
//  OVDF sample frames: per (face, i, j) two texels, x and z (y = z × x); then
//    per shell one texel (table zoom, cone radius, 0, 0) (src/fields/ovdf.h OvdfZoom);
//    then per sample (surface distance, occluded area), kSamplesPerTexel
//    samples to a texel;
//    then the radial spans, (enter, exit) of two lines to a texel. The
//    part record's kSlotOvdfRecords holds where the last three start.
//
// The shader writes none of these numbers: shader_layout_constants() turns
// kShaderIntConstants (and π, √2) into GLSL constants that the host prepends
// to the shading pass, so this header is their one source.
//  BRDF: one 3D texture 2(N+1)×(N+1)×slices, per slice its corner sums beside
//    its texels (append_texture_rows), all tables stacked along z; per slice
//    its mean offset (RGB)
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "src/brdf/brdf_table.h"
#include "src/core/scene.h"
#include "src/gl/gpu_interface.h"
#include "src/render/occluder_culling.h"
#include "src/render/frame_setup.h"
#include "src/render/part_fields.h"
#include "src/render/vertex_blocks.h"
#include "src/shading/pbr_basis.h"
#include "src/shading/shapes.h"

namespace rsl::gl {

// Width of every array texture (gl_objects.h): a power of two, so that the
// shader splits an index with a mask and a shift.
inline constexpr int kArrayTextureWidth = 2048;
inline constexpr int kArrayTextureShift = 11;
static_assert(1 << kArrayTextureShift == kArrayTextureWidth);

inline constexpr int kPartStride = 30;
// Texel slots inside a part record.
enum PartSlot : int {
    kSlotTransform = 0,   // 4 columns
    kSlotNormal = 4,      // 3 columns
    kSlotInverse = 7,     // 4 columns
    kSlotMaterial = 11,   // (first slice, isotropic: 1, and view-independent: 2, else 0; V, 0)
    kSlotSvdf = 12,       // (tables base, coefficients base, resolution (0: none), stride)
    kSlotVertices = 13,   // (first vertex, 0, 0, 0)
    kSlotOvdfCenter = 14, // (center, radius (0: none))
    kSlotOvdfBases = 15,  // (tables base, coefficients base, frames base, outer shell radius)
    kSlotOvdfShells = 16, // (shells, spacing, inner radius, outer radius)
    kSlotOvdfGrid = 17,   // (cube resolution, VDT resolution, stride, segments per side)
    kSlotBoxLow = 18,     // (the mesh's bounding box low corner, 0): the slab rule (square_lights.h)
    kSlotBoxHigh = 19,    // (high corner, 0)
    kSlotOvdfRecords = 20, // (first shell zoom record, first surface-distance texel, first span texel, span resolution (0: none)), in the frames texture
    kSlotSpecular = 21,    // textured part: its specular table as kSlotMaterial, w = 1; else all 0
    // A part of exact shape (src/render/occluder_shape.h): (center, kind), (s, 0), (t, 0), (normal, 0)
    // and the shape's (lo, hi) in those coordinates; kind 0 (shading::kShapeNone) for other parts.
    kSlotShape = 22,
    kSlotShapeS = 23,
    kSlotShapeT = 24,
    kSlotShapeNormal = 25,
    kSlotShapeLow = 26,
    kSlotShapeHigh = 27,
    kSlotDiffuseLight = 28,  // (the BRDF's constant term a, 0): the exact diffuse light (src/shading/diffuse_light.h)
    kSlotPbr = 29,  // (base colour factor, 1) for a material varying per point (src/shading/pbr_basis.h), else 0
};
static_assert(kSlotPbr < kPartStride);
// The basis tables of materials varying per point (PbrBasisTables): D, then
// S(0.04, level j), then S(1, level j); the shader's u_pbr_basis.
inline constexpr int kPbrBasisRecords = 1 + 2 * shading::kPbrLevels;

inline constexpr int kLightTexels = 3;        // per light in the lights texture
// The vertex pass's storage buffers (shaders/shade_blocks.comp.glsl).
// Per candidate (pack_block_candidates): occluder, growth's bits, then its light words.
inline constexpr int kCandidateHeader = 2;
// Per part, kCullingStride vec4 (pack_part_culling).
enum CullingSlot : int {
    kCullingBounds = 0,  // the part's world bounding sphere (center, radius)
    kCullingReach = 1,   // its occluder field's reach in the world (radius 0: none)
    kCullingField = 2,   // its split-lookup OVDF's bounding sphere in the world
    kCullingFlags = 3,   // (uniform scale, split lookup, 0, 0)
    kCullingStride = 4,
};
// The vertex pass's counters (GlRenderer::device_counts), uints.
enum Counter : int {
    kCounterOccluderLookups = 0,
    kCounterBlockPairs = 1,        // (block, light, occluder) triples the part-level lists hand the blocks
    kCounterBlockPairsCulled = 2,  // ... of which the block-level tests culled
    kCounterShadowRays = 3,        // rays traced (RenderOptions::gpu_rays)
    kCounterCount = 4,
};
inline constexpr int kOvdfFrameTexels = 2;    // per OVDF sample frame (x, z)
inline constexpr int kSamplesPerTexel = 2;    // OVDF samples' (surface distance, occluded area), RG and BA

// The integer constants the shading pass reads, by their GLSL names.
inline constexpr GlslConstant kShaderIntConstants[] = {
    {"kArrayWidth", kArrayTextureWidth},
    {"kArrayShift", kArrayTextureShift},
    {"kPartStride", kPartStride},
    {"kSlotTransform", kSlotTransform},
    {"kSlotNormal", kSlotNormal},
    {"kSlotInverse", kSlotInverse},
    {"kSlotMaterial", kSlotMaterial},
    {"kSlotSvdf", kSlotSvdf},
    {"kSlotVertices", kSlotVertices},
    {"kSlotOvdfCenter", kSlotOvdfCenter},
    {"kSlotOvdfBases", kSlotOvdfBases},
    {"kSlotOvdfShells", kSlotOvdfShells},
    {"kSlotOvdfGrid", kSlotOvdfGrid},
    {"kSlotBoxLow", kSlotBoxLow},
    {"kSlotBoxHigh", kSlotBoxHigh},
    {"kSlotOvdfRecords", kSlotOvdfRecords},
    {"kSlotSpecular", kSlotSpecular},
    {"kSlotShape", kSlotShape},
    {"kSlotShapeS", kSlotShapeS},
    {"kSlotShapeT", kSlotShapeT},
    {"kSlotShapeNormal", kSlotShapeNormal},
    {"kSlotShapeLow", kSlotShapeLow},
    {"kSlotShapeHigh", kSlotShapeHigh},
    {"kSlotDiffuseLight", kSlotDiffuseLight},
    {"kSlotPbr", kSlotPbr},
    {"kPbrBasisRecords", kPbrBasisRecords},
    {"kLightTexels", kLightTexels},
    {"kShadeBlock", kShadeBlock},
    {"kCandidateHeader", kCandidateHeader},
    {"kCullingBounds", kCullingBounds},
    {"kCullingReach", kCullingReach},
    {"kCullingField", kCullingField},
    {"kCullingFlags", kCullingFlags},
    {"kCullingStride", kCullingStride},
    {"kCounterOccluderLookups", kCounterOccluderLookups},
    {"kCounterBlockPairs", kCounterBlockPairs},
    {"kCounterBlockPairsCulled", kCounterBlockPairsCulled},
    {"kCounterShadowRays", kCounterShadowRays},
    {"kSamplesPerTexel", kSamplesPerTexel},
};

// GLSL declarations of kShaderIntConstants and of kPi and kSqrt2 (the
// shading core's, printed so that they read back as the same floats), one
// `const` per line, then the storage bindings (gpu_interface.h
// shader_interface_glsl), for the host to prepend to the shading pass.
std::string shader_layout_constants();

// Where a block (one field's tables, coefficients, frames, spans) starts in
// a flat array after `size` texels. The part records hold block starts in
// float texels, and a float holds every integer below 2^24 but beyond it
// only multiples of a power of two: starting every block at a multiple of
// kBlockAlign keeps its start exact up to 2^24 · kBlockAlign texels, past any
// texture a driver allows (the robot's 32-shell OVDF tables are 18.9 M
// texels; the limit was 2^24 before).
inline constexpr size_t kBlockAlign = 64;
inline size_t block_start(size_t size) { return (size + kBlockAlign - 1) / kBlockAlign * kBlockAlign; }

// Texels of a reconstruction row or coefficient row for k basis vectors.
inline int cpca_stride(int vectors) { return (vectors + 1 + 3) / 4; }
// `shared` (PackedGeometry::svdf_stride, ovdf_stride) after a field of `stride`.
inline int shared_stride(int shared, int stride) { return shared == 0 || shared == stride ? stride : -1; }

struct PackedGeometry {
    std::vector<Vec4> positions, normals, tangents;  // per vertex (the vertex rectangle)
    std::vector<int> first_vertex;                   // per part, and the total at the end
    std::vector<Vec4> part_static;                   // parts × kPartStride (pose slots left 0)
    std::vector<Vec4> svdf_tables, svdf_coefficients;
    std::vector<Vec4> ovdf_tables, ovdf_coefficients, ovdf_frames;
    bool svdf_tables_half = true, ovdf_tables_half = true;  // every table value exactly a half
    int max_stride = 1;
    // The stride every SVDF (OVDF) shares: the shaders' loops over a row then
    // have a constant count; 0 when there is none, -1 when strides differ.
    int svdf_stride = 0, ovdf_stride = 0;
    std::array<Vec3, 6> face_normal{}, face_s{}, face_t{};  // OVDF cube faces (as Ovdf::prepare)
};

// Packs meshes and fields. Occluder fields must be OvdfOccluder (the
// compressed field); others throw rsl::Error naming the scene. With
// `exact_shapes` (RenderOptions), parts of exact shape get their kSlotShape*
// records.
PackedGeometry pack_geometry(const Scene& scene, const PartFields& fields, bool exact_shapes = false);

struct PackedMaterials {
    int resolution = 0;  // N
    int slices = 0;
    std::vector<float> texture;  // 2(N+1) × (N+1) × slices × RGB: append_texture_rows of each table
    std::vector<Vec4> offsets;   // per slice
    std::vector<Vec4> part_material;  // per part: (first slice, isotropic, V, 0)
    std::vector<Vec4> part_specular;  // per part: (first slice, isotropic, V, 1), or 0 without a specular table
    std::vector<Vec4> pbr_basis;      // kPbrBasisRecords: each basis table's record, or 0 where not built
};

// A table's slices as the BRDF texture holds them: per slice N+1 rows of
// 2(N+1) RGB entries, a row of corner sums, then the same row of texels
// (BrdfTable::lookup_data() has them as two layers; the texture's depth,
// which holds the slices, is too short for twice as many).
void append_texture_rows(const BrdfTable& table, std::vector<float>& out);

// The kSlotMaterial / kSlotSpecular record of a table whose slices start at
// `first_slice`; `specular` sets w (the shader's "layered" flag).
Vec4 material_record(const BrdfTable& table, int first_slice, bool specular);

// Stacks the distinct tables the parts use (same N required): each part's
// table, and its specular table where `part_specular_tables` (empty, or one
// per part, null for untextured parts) has one.
PackedMaterials pack_materials(const std::vector<std::shared_ptr<const BrdfTable>>& part_tables,
                               const std::vector<std::shared_ptr<const BrdfTable>>& part_specular_tables = {},
                               const std::vector<std::shared_ptr<const BrdfTable>>& pbr_basis_tables = {});

// The pose slots of one part record.
void write_pose(const Mat4& transform, const Mat3& normal, const Mat4& inverse, Vec4* record);

// The CPU renderer's vertex blocks (vertex_blocks.h) as the vertex pass's
// workgroups take them: per block (part, first entry of `vertices`, vertex
// count, 0), and per entry the vertex's index in the vertex rectangle.
struct PackedBlocks {
    std::vector<glm::ivec4> blocks;
    std::vector<int32_t> vertices;
};
PackedBlocks pack_blocks(const Scene& scene, const std::vector<int>& first_vertex);

// The frame's per-part candidates (OccluderLists::candidate_*) as the vertex
// pass reads them: parts + 1 offsets (in candidates), then per candidate
// kCandidateHeader + lists.light_words words. Throws rsl::Error past what
// uint words index.
void pack_block_candidates(const OccluderLists& lists, std::vector<uint32_t>& words);

// What the block-level tests need of each part in this frame
// (kCullingStride vec4 per part, CullingSlot): `local_reach` its occluder
// field's reach in its own frame (radius 0: none), `split_fields` its
// split-lookup OVDF's (split_lookup_field) bounding sphere (radius 0: none).
void pack_part_culling(const std::vector<PartPose>& poses, const std::vector<BoundingSphere>& local_reach,
                       const std::vector<BoundingSphere>& split_fields, std::vector<Vec4>& out);

}  // namespace rsl::gl
