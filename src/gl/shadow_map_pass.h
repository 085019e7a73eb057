#pragma once
// The depth pass of the shadow-mapped many-light baseline
// (RenderOptions::shadow_maps; docs/design/GPU_DESIGN.md, "Shadow-mapped visibility"): a
// competitor to the RSL visibility, not part of the RSL method.
//
// Per environment square light, one orthographic depth map along the
// light's centre direction; every part is drawn into layer l of one
// GL_TEXTURE_2D_ARRAY (DEPTH_COMPONENT32F, resolution² × lights). The maps
// span one sphere around the posed scene (every part's world bounding
// sphere), through the shading core's shadow_map_point, which the shading
// pass calls too, so a vertex finds itself where it was drawn. The shading
// pass reads the depths with texelFetch and compares each texel itself
// (with the receiver's plane at that texel: shaders/shadow_map_filter.glsl).
#include <cstddef>
#include <span>
#include <vector>

#include "src/gl/gl_objects.h"
#include "src/render/frame_setup.h"

namespace rsl::gl {

// Throws rsl::Error unless the resolution lies in
// [ShadowMapOptions::kMinResolution, kMaxResolution] and pcf_distance > 0.
void check_shadow_map_options(const ShadowMapOptions& options);

// A sphere (centre, radius) holding every part's world bounding sphere,
// grown by 1 % so that no triangle touches the maps' faces.
Vec4 shadow_map_sphere(const std::vector<PartPose>& poses);

// The parts' triangles as the display pass draws them: its vertex array
// (attribute 0 = part-space positions, and the index buffer), per part the
// first index (and the total at the end) and the first vertex.
struct ShadowCasters {
    GLuint vertex_array = 0;
    std::span<const size_t> first_index;
    std::span<const int> first_vertex;
};

class ShadowMaps {
public:
    ShadowMaps();  // needs a current context: the depth program

    // Every part into each square's layer, at `resolution` texels per side.
    // The array is re-allocated only when the resolution or the number of
    // squares changes; rsl::Error when the driver cannot hold it.
    void render(int resolution, const std::vector<PartPose>& poses, const std::vector<SquareLight>& squares,
                const ShadowCasters& casters);

    Vec4 sphere() const { return sphere_; }  // of the last render
    int resolution() const { return resolution_; }
    int layers() const { return layers_; }
    size_t bytes() const { return size_t(resolution_) * size_t(resolution_) * size_t(layers_) * 4; }
    // The array on texture unit `unit`, and the shading pass's uniforms of
    // the maps and the filter (shaders/shadow_map_filter.glsl, u_shadow_*);
    // `shading` in use.
    void bind_for_shading(const Program& shading, const ShadowMapOptions& options, int unit) const;

private:
    void allocate(int resolution, int layers);

    Program program_;
    Texture depths_;
    Framebuffer framebuffer_;
    int resolution_ = 0, layers_ = 0;
    Vec4 sphere_{0.0f};  // radius 0 until the first render
};

}  // namespace rsl::gl
