#pragma once
// The viewer's background: the environment map (and a blend's second map) as
// a cube-map texture, drawn behind the scene, turned as the renderer turns
// its lights. Texels are the CubeMap's own (OpenGL face order and (s, t)
// orientation, docs/design/CONVENTIONS.md), sampled nearest: the background shows
// exactly the radiance the renderer's lights were fitted to.
#include "src/core/envmap.h"
#include "src/gl/gl_objects.h"

namespace rsl::gl {

class Skybox {
public:
    // `second` may be null (no blend). Needs a current GL 3.3 core context (the renderer beside it needs 4.3).
    Skybox(const CubeMap& first, const CubeMap* second);

    // Fills the bound framebuffer's viewport (depth test off, depth
    // untouched): pixel → world view direction d → (1 − w)·L₁(Rᵀd) + w·L₂(Rᵀd),
    // times `exposure`, sRGB-encoded. R: the environment's rotation at the
    // frame (the scene's at t, and the viewer's turn).
    void draw(const Mat4& view_projection, const Vec3& eye, const Mat3& rotation, float second_weight, float exposure);

private:
    Program program_;
    Texture first_, second_;
    VertexArray vao_;
};

}  // namespace rsl::gl
