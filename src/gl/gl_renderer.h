#pragma once
// The GPU runtime renderer (RSL paper §5.2): the CPU renderer's sum
// (src/render/renderer.h) as a render-to-vertex-array pass.
//
//  1. Shading pass: a fragment shader runs over the "vertex rectangle" — one
//     texel per vertex of every part, W = 2048 wide — and writes each vertex's
//     RGB into an RGBA32F render target (shaders/shade_vertices.frag.glsl).
//  2. The target is read into a pixel-pack buffer (GPU to GPU, no CPU copy),
//     and that same buffer is bound as the vertex-colour array.
//  3. Display pass: the parts drawn with those colours (shaders/display.*).
//
// Everything static (meshes, SVDF, OVDF, BRDF tables) is uploaded once
// (gpu_layout.h); every frame uploads part poses, lights and occluder masks
// (a few KB). Needs a current OpenGL ≥ 3.3 core context for its lifetime.
#include <memory>
#include <vector>

#include "lightfit/rsl.h"
#include "src/core/scene.h"
#include "src/gl/frame_state.h"
#include "src/gl/gl_objects.h"
#include "src/gl/gpu_layout.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/trace/vertex_colors.h"

namespace rsl::gl {

// GPU time of each pass of the last frame whose timer queries are done (ms).
struct PassTimings {
    double shade_ms = 0, pack_ms = 0, display_ms = 0;
};

class GlRenderer {
public:
    // `scene` must outlive the renderer. Tables: the scene's materials with
    // options.material_override applied (as the CPU renderer's MaterialTables).
    GlRenderer(const Scene& scene, RslSet environment_lights, PartFields fields, const RenderOptions& options);
    ~GlRenderer();

    // Poses, lights and camera at time t (the scene's camera), as Renderer::set_time.
    void set_time(float t);
    // The viewer's variant: its own camera and an extra environment rotation.
    void set_view(float t, const Vec3& camera, const Mat3& environment_rotation);
    float time() const { return time_; }

    // Runs the shading pass and fills the vertex-colour buffer (on the GPU).
    void shade();
    // Copies the vertex-colour buffer to the CPU (tests, `rsl render --backend gl`).
    VertexColors make_output() const;
    void read_colors(VertexColors& out) const;
    VertexColors shade_and_read() {
        shade();
        VertexColors out = make_output();
        read_colors(out);
        return out;
    }

    // Display pass into the bound framebuffer (depth test on, caller clears).
    void draw(const Mat4& view_projection, float exposure);

    // Live changes (the viewer): visibility/light toggles of `options` (not
    // material overrides or table options, which go through set_part_tables).
    void set_toggles(const RenderOptions& options);
    const RenderOptions& options() const { return options_; }
    void set_environment_lights(RslSet lights);
    const RslSet& environment_lights() const { return environment_; }
    // One table per part; re-uploads the stacked BRDF texture.
    void set_part_tables(std::vector<std::shared_ptr<const BrdfTable>> tables);
    const std::vector<std::shared_ptr<const BrdfTable>>& part_tables() const { return part_tables_; }

    const FrameState& frame() const { return frame_; }
    PassTimings timings() const { return timings_; }
    size_t gpu_bytes() const { return gpu_bytes_; }
    GLuint color_buffer() const { return colors_.id(); }
    int vertex_count() const { return vertex_count_; }

private:
    void upload_geometry(const PackedGeometry& geometry);
    void upload_frame();
    void collect_timings();

    const Scene& scene_;
    RenderOptions options_;
    RslSet environment_;
    PartFields fields_;
    std::vector<std::shared_ptr<const BrdfTable>> part_tables_;
    FrameState frame_;
    float time_ = 0;
    int vertex_count_ = 0, rect_height_ = 1;
    std::vector<int> first_vertex_;
    std::vector<Vec4> part_records_;
    std::vector<Vec4> light_texels_;
    PackedMaterials materials_;
    size_t gpu_bytes_ = 0;

    Program shade_program_, display_program_;
    Texture positions_, normals_, tangents_;
    ArrayTexture parts_, lights_, brdf_offsets_;
    ArrayTexture svdf_tables_, svdf_coefficients_, ovdf_tables_, ovdf_coefficients_, ovdf_frames_;
    Texture occluders_, brdf_;
    Texture target_;
    Framebuffer target_fbo_;
    Buffer colors_;  // GL_PIXEL_PACK_BUFFER when written, GL_ARRAY_BUFFER when drawn
    VertexArray empty_vao_, display_vao_;
    Buffer display_positions_, display_indices_;
    std::vector<size_t> first_index_;  // per part, into display_indices_, and the total
    Query queries_[2][3];              // [frame parity][pass]
    bool query_pending_[2] = {false, false};
    bool drew_[2] = {false, false};  // whether the display query ran
    int frame_parity_ = 0;
    PassTimings timings_;
};

// The per-part BRDF tables of the scene with the options' material overrides.
std::vector<std::shared_ptr<const BrdfTable>> scene_part_tables(const Scene& scene, const RenderOptions& options);

}  // namespace rsl::gl
