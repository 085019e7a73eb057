#pragma once
// The GPU runtime renderer: the CPU renderer's sum (src/render/cpu_renderer.h)
// as a compute pass over the CPU's own vertex blocks
// (docs/design/GPU_DESIGN.md "The vertex pass").
//
//  1. Vertex pass: one workgroup per vertex block (shaders/shade_blocks.comp.glsl)
//     builds the block's occluder lists from the frame's part-level
//     candidates with the CPU's block-level culling tests
//     (src/shading/culling.h), and writes each vertex's RGB into the
//     vertex-colour buffer, which the display pass draws as it is.
//  2. Display pass: the parts drawn with those colours (shaders/display.*),
//     and the parts shaded per pixel (RenderOptions::pixel_shadows: the
//     flat rectangles, grounds and walls; pixel_highlights: glossy parts)
//     drawn by the per-pixel pass, which takes the whole sum at the point
//     each pixel sees (shaders/shade_pixels.*, gl_display.cpp).
//
// Everything static (meshes, blocks, SVDF, OVDF, BRDF tables) is uploaded
// once (gpu_layout.h); every frame uploads part poses, lights and occluder
// candidates (a few KB). Needs a current OpenGL ≥ 4.3 core context for its
// lifetime; an older one gets rsl::Error.
//
// It is a VertexRenderer (src/render/vertex_renderer.h): the frame of time t
// comes from the shared FrameSetup, the BRDF tables from its MaterialLibrary;
// before a frame, a material whose revision() changed has its table
// re-uploaded into its own slices of the stacked BRDF texture (only a change
// of the tables' layout, e.g. isotropic → anisotropic, re-packs them all).
//
// A second competitor, RenderOptions::gpu_rays (GL only; docs/design/GPU_DESIGN.md
// "Ray-traced visibility"), takes every light's visibility from the CPU
// ray-traced rows' S×S jittered rays, traced by the vertex pass through a
// BVH of the posed parts (ray_traced_visibility.h).
//
// A competitor baseline rides along (RenderOptions::shadow_maps, GL only;
// docs/design/GPU_DESIGN.md "Shadow-mapped visibility"): with it enabled, each frame first
// draws one depth map per environment RSL (shadow_maps.h), and the vertex
// pass takes every environment light's visibility from its map, filtered
// over the light's square (PCF or PCSS), instead of SVDF × Π OVDF; local
// lights keep the fields. From C++: options.shadow_maps.enabled = true
// (resolution, filter) before make_renderer(Backend::Gl, …), or
// set_toggles() between frames.
#include <memory>
#include <vector>

#include "src/lightfit/square_light.h"
#include "src/core/scene.h"
#include "src/gl/gl_objects.h"
#include "src/gl/gpu_layout.h"
#include "src/gl/ray_traced_visibility.h"
#include "src/gl/shadow_map_pass.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/formats/vertex_colors.h"
#include "src/render/vertex_renderer.h"

namespace rsl::gl {

// GPU time of each pass (ms): of the last frame whose timer queries are
// done, or, where timer queries measure nothing (software rasterizers, see
// gl_renderer.cpp), of the last frame by the CPU clock around glFinish.
// shadow_ms: the shadow-map depth pass (RenderOptions::shadow_maps), 0 for
// a frame that drew none (maps off, or nothing moved since the last maps).
struct PassTimings {
    double shade_ms = 0, display_ms = 0, shadow_ms = 0;
    bool clock = false;  // measured by the CPU clock around glFinish
};

// What the last vertex pass counted (read back from the GPU).
struct DeviceCounts {
    size_t occluder_lookups = 0;      // (vertex, light, occluder) lookups, as RenderStats::occluder_lookups
    size_t block_pairs = 0;           // (block, light, occluder) triples the part-level lists hand the blocks
    size_t block_pairs_culled = 0;    // ... of which the block-level tests culled
    size_t shadow_rays = 0;           // rays traced (RenderOptions::gpu_rays)
};

// How the BRDF texture was last brought up to date (counted since construction).
struct MaterialUploads {
    int full = 0;    // every table packed and uploaded
    int tables = 0;  // single tables uploaded into their own slices
};

class GlRenderer : public VertexRenderer {
public:
    // As VertexRenderer's constructor (vertex_renderer.h); needs a current
    // OpenGL ≥ 4.3 core context for its lifetime (rsl::Error otherwise).
    GlRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields, const RenderOptions& options);
    ~GlRenderer() override;

    std::string backend() const override { return "gl"; }

    // Runs the vertex pass and fills the vertex-colour buffer (on the GPU;
    // the viewer draws it as it is).
    void shade_on_device();
    // shade_on_device() and the colours copied to the CPU; stats() gets the
    // pass's counts (device_counts()).
    void shade(VertexColors& out) override;
    using VertexRenderer::shade;
    // The vertex colours of the last shade_on_device(), into `out`; textured
    // parts get two layers (match_layers), as the CPU renderer's.
    void read_colors(VertexColors& out) const;

    // Display pass into the bound framebuffer (depth test on, caller clears):
    // the vertex colours' blend, and the per-pixel pass for the parts shaded
    // per pixel (per_pixel_part). sRGB at `exposure`.
    void draw(const Mat4& view_projection, float exposure);
    // Whether the display pass shades part p per pixel: the parts that are
    // one flat rectangle (find_rectangle), unless options().pixel_shadows is
    // Off, and the glossy ones (material not Lambert, untextured) while
    // options().pixel_highlights is on, as the CPU's. Others
    // (PixelShadows::All's Lambert curved parts too) are their vertex
    // colours' blend on the GPU.
    bool per_pixel_part(size_t p) const;
    bool highlight_part(size_t p) const;

    // Live changes (the viewer): visibility/light toggles of `options` and
    // its shadow maps (not material overrides or table options: materials()
    // is the library). Throws rsl::Error for shadow-map options out of range.
    void set_toggles(const RenderOptions& options);
    MaterialUploads material_uploads() const { return uploads_; }

    PassTimings timings() const { return timings_; }
    // The last vertex pass's counts (waits for it).
    DeviceCounts device_counts() const;
    // Per block (CpuRenderer::block_candidate_lights' order and layout) the
    // light words the workgroup kept for each candidate occluder at the
    // current frame: a vertex pass of its own, for tests.
    std::vector<std::vector<uint32_t>> block_candidate_lights();
    // "shadow maps 3.1 ms, shading 40.2 ms (clock)": the last measured frame.
    std::string pass_times() const override;
    // The shadow maps' sphere (centre, radius) of the last frame that drew them; (0, 0, 0, 0) before.
    Vec4 shadow_map_sphere() const { return shadow_maps_ ? shadow_maps_->sphere() : Vec4(0.0f); }
    size_t gpu_bytes() const {
        return gpu_bytes_ + (shadow_maps_ ? shadow_maps_->bytes() : 0) + (rays_ ? rays_->bytes() : 0);
    }
    GLuint color_buffer() const { return colors_.id(); }
    int vertex_count() const { return vertex_count_; }

protected:
    // The display pass's image at `camera`, read back (draw_image), S× as
    // large for S×S samples and resolved to one pixel each.
    Image backend_image(const VertexColors& colors, const PinholeCamera& camera,
                        const ImageFormationOptions& options) override;
    // The shadow maps and the shaded colours are stale, the frame's occluder
    // lists flattened for the shader.
    void frame_changed() override;

private:
    // The image the display pass draws at `camera`, in linear radiance,
    // read back: RGBA, alpha the coverage (0 or 1: one sample per pixel, at
    // its centre), row 0 at the top. After shade_on_device(); the camera's
    // pose is the caller's (the vertex colours' view is the frame's camera).
    Image draw_image(const PinholeCamera& camera);
    void upload_geometry(const PackedGeometry& geometry);
    // What the vertex pass and the per-pixel pass are compiled for (their
    // defines): they are built again when the frame needs another, e.g. when
    // the light count crosses a multiple of 32 or the first textured
    // material comes.
    struct VertexPassVariant {
        size_t light_words = 0;     // LIGHT_WORDS (32 lights a word)
        bool layered = false;       // LAYERED: the specular layer
        bool rays = false;          // RAY_TRACED: ray-traced visibility
        bool shadow_maps = false;   // SHADOW_MAPPED: the shadow-map branch
        bool local_lights = false;  // LOCAL_LIGHTS: the frame has sphere lights
        int slices = 0;             // MAX_SLICES: BRDF slices an average blends, the most over the parts' tables
        bool operator==(const VertexPassVariant&) const = default;
    };
    VertexPassVariant frame_vertex_pass_variant() const;
    // The passes' defines for `variant` (RECORD_BLOCK_LIGHTS: `record`).
    std::string variant_defines(const VertexPassVariant& variant, bool record) const;
    Program make_vertex_pass(const VertexPassVariant& variant, bool record);
    // The per-pixel pass for the frame's variant (no ray-traced branch).
    Program make_pixel_pass(VertexPassVariant variant);
    // Dispatches `program` (a vertex pass) over every block.
    void run_vertex_pass(const Program& program);
    // The sampler units and the OVDF cube faces' uniforms of a program that shades (shading_data.glsl).
    void set_sampler_units(const Program& program);
    void upload_frame();
    // Brings the BRDF texture up to the library: in place when only tables of
    // the same layout changed, else a full pack (upload_all_tables).
    void sync_materials();
    void upload_all_tables();
    // Per part its table, then per part its specular table (null: untextured).
    std::vector<std::shared_ptr<const BrdfTable>> wanted_tables() const;
    // Entry i of wanted_tables() into its part record (kSlotMaterial or kSlotSpecular).
    void write_material_record(size_t i, const BrdfTable* table, int first_slice);
    void set_part_tables(std::vector<std::shared_ptr<const BrdfTable>> tables);
    // The depth maps of the frame's environment squares, when enabled and
    // the frame changed since the last ones (update_frame marks them stale).
    void render_shadow_maps();
    // The shading textures and the frame's uniforms, for the vertex pass or the per-pixel pass.
    void bind_shading_inputs(const Program& program);
    void bind_shadow_uniforms(const Program& program);
    void draw_parts(const Mat4& view_projection, float exposure, bool linear, GLenum depth_test);
    void collect_timings();
    // Time a pass (kPass*): a timer query, or the clock.
    void begin_pass(int pass);
    void end_pass(int pass);

    // What the BRDF texture holds: per part its table then per part its
    // specular table (wanted_tables() order), per distinct table its slices
    // (first, count); layered_: some part has a specular table.
    // Then the basis tables of materials varying per point (kPbrBasisRecords,
    // null where not built), whose records go to u_pbr_basis.
    std::vector<std::shared_ptr<const BrdfTable>> part_tables_;
    bool layered_ = false;
    std::vector<Vec4> pbr_basis_records_;
    // Per vertex (roughness, metallic) of the parts whose material varies per
    // point (src/brdf/pbr_basis.h), written when a part's material changes.
    ArrayTexture pbr_points_;
    void upload_pbr_points();
    int brdf_tiles_ = 1;  // BRDF slices per depth layer of brdf_, stacked along y
    void upload_brdf_slices(int first, int count, const float* data);
    struct TableSlot {
        std::shared_ptr<const BrdfTable> table;
        int first_slice = 0, slices = 0;
    };
    std::vector<TableSlot> slots_;
    MaterialUploads uploads_;
    // Whether the colour buffer holds the current frame's shading (the
    // display pass draws it with the current frame's poses and lights).
    bool shaded_current_frame_ = false;
    int vertex_count_ = 0, rect_height_ = 1;
    std::vector<int> first_vertex_;
    std::vector<Vec4> part_records_;
    std::vector<Vec4> light_texels_;
    int irradiance_first_ = -1, irradiance_second_ = -1;  // the irradiance maps' first texels in lights_ (-1: none)
    PackedMaterials materials_;
    size_t gpu_bytes_ = 0;

    Program vertex_pass_, display_program_, pixel_program_;
    std::string vertex_pass_defines_;  // MAX_STRIDE, SVDF_STRIDE, OVDF_STRIDE
    VertexPassVariant vertex_pass_variant_;  // what vertex_pass_ was built for
    VertexPassVariant pixel_pass_variant_;   // ... and pixel_program_ (built on first use)
    std::vector<Vec3> face_normal_, face_s_, face_t_;  // the OVDF cube faces' uniforms
    std::vector<char> rectangle_parts_;  // per part: one flat rectangle (find_rectangle)
    std::vector<Bounds> part_bounds_;  // per part: its mesh's box (part space)
    ArrayTexture positions_, normals_, tangents_;
    // Skinned parts (src/core/skinning.h): the packed vertex texels, whose
    // skinned parts' rows upload_skinned_vertices rewrites each frame with
    // the frame's posed vertices, and each part's first display vertex.
    std::vector<Vec4> packed_positions_, packed_normals_, packed_tangents_;
    std::vector<size_t> display_first_vertex_;
    bool skinned_ = false;
    void upload_skinned_vertices();
    ArrayTexture parts_, lights_, brdf_offsets_;
    ArrayTexture indices_;         // every part's triangle indices (part-local), first_index_ order
    ArrayTexture svdf_tables_, svdf_coefficients_, ovdf_tables_, ovdf_coefficients_, ovdf_frames_;
    Texture brdf_;
    // The vertex pass's storage buffers (gpu_layout.h): the blocks and
    // their vertices (static); the frame's candidates and part culling
    // records; the counters.
    Buffer blocks_, block_vertices_, candidates_, part_culling_, counters_;
    int block_count_ = 0;
    std::vector<int> block_parts_;  // per block its part
    std::vector<uint32_t> candidate_words_;
    std::vector<Vec4> part_culling_records_;
    std::vector<BoundingSphere> local_reach_, split_fields_;  // per part (pack_part_culling)
    // Written by the vertex pass as a storage buffer, drawn as GL_ARRAY_BUFFER:
    // per vertex its colour, then (layered_ only) the specular layer at layer_bytes_.
    Buffer colors_;
    size_t layer_bytes_ = 0;  // one vertex rectangle of RGBA32F
    VertexArray empty_vao_, display_vao_;
    Buffer display_positions_, display_texcoords_, display_indices_;
    // Base colour and emissive textures of the display and per-pixel passes, uploaded at their first draw.
    std::vector<std::pair<std::shared_ptr<const rsl::Texture>, Texture>> base_colors_;
    GLuint base_color_texture(const std::shared_ptr<const rsl::Texture>& texture);
    // A material texture on the GPU (uploaded on `unit` at its first use, kept in base_colors_).
    GLuint uploaded_texture(const std::shared_ptr<const rsl::Texture>& texture, int unit);
    std::vector<size_t> first_index_;  // per part, into display_indices_, and the total
    std::unique_ptr<ShadowMaps> shadow_maps_;  // made when first enabled
    std::unique_ptr<RayTracedVisibility> rays_;  // made when options_.gpu_rays is first enabled
    bool shadow_maps_stale_ = true;
    Query queries_[2][4];              // [frame parity][pass]
    bool query_pending_[2] = {false, false};
    bool drew_[2] = {false, false};      // whether the display query ran
    bool shadowed_[2] = {false, false};  // whether the shadow-map query ran
    int frame_parity_ = 0;
    PassTimings timings_;
    bool clock_timing_ = false;  // timer queries of this driver measure nothing
    double pass_start_ms_ = 0;
};

}  // namespace rsl::gl
