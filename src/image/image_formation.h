#pragma once
// Image formation shared by the ground truth and the RSL renderer, so that
// images compare like for like: primary rays from the scene camera through a
// regular S×S grid of sample positions in every pixel (S = 1: the pixel
// center); a sample that hits a triangle takes a colour from the hit, the
// pixel is the average over its samples (background counted as black unless a
// background is given) and alpha is the covered fraction. EXR convention:
// colour is premultiplied by coverage.
#include <functional>
#include <vector>

#include "src/core/envmap.h"
#include "src/core/image.h"
#include "src/core/scene.h"
#include "src/rays/posed_scene.h"
#include "src/core/progress.h"
#include "src/formats/vertex_colors.h"

namespace rsl {

// Pinhole camera at time t: row 0 at the top, vertical field of view from
// Camera::fov_y_degrees, square pixels.
struct PinholeCamera {
    Vec3 eye{0}, forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};
    float tan_half_fov_y = 0.36f;
    int width = 640, height = 480;

    static PinholeCamera at_time(const Camera& camera, float t, int width, int height);
    // Unit direction through image position (px, py) in pixels: (0, 0) is the
    // top-left corner of the image, (width, height) the bottom-right.
    Vec3 direction(float px, float py) const { return direction_through(screen_x(px), screen_y(py)); }

    // The same in two steps, for batches of rays (bit for bit the same
    // direction): image-plane coordinates at unit distance, then the unit
    // direction through them.
    float screen_x(float px) const {
        const float aspect = float(width) / float(height);
        return (2.0f * px / float(width) - 1.0f) * tan_half_fov_y * aspect;
    }
    float screen_y(float py) const { return (1.0f - 2.0f * py / float(height)) * tan_half_fov_y; }
    Vec3 direction_through(float sx, float sy) const { return glm::normalize(forward + sx * right + sy * up); }
};

struct ImageFormationOptions {
    int samples_per_side = 1;  // S: S×S samples per pixel on a regular grid
    bool opaque_background = false;
    Color background{0};  // used when opaque_background: uncovered samples add this colour
};

// Colour of a primary-ray hit (called from worker threads).
using HitShader = std::function<Color(const RayHit& hit, const Vec3& ray_direction)>;

// Per part, a shader that colours its hits in place of the vertex colours'
// blend (an empty function, or a part past the end: the blend). What a
// renderer shades per pixel (VertexRenderer::pixel_shading).
using PartShaders = std::vector<HitShader>;

// Traces the image; every hit is coloured by `shade`. RGBA, all cores. Rays
// are traced in coherent packets over square tiles of pixels, and each pixel
// sums its samples in the order a ray at a time would (same hits, same sums).
Image trace_image(const PosedScene& scene, const PinholeCamera& camera, const ImageFormationOptions& options,
                  const HitShader& shade, const ProgressCallback& progress = {});

// The reference for trace_image: the same primary rays traced one at a time
// (rows in parallel), each pixel's samples summed in the same (b, a) order, so
// that packets must give the same image. For tests and benchmarks.
Image trace_image_one_ray_at_a_time(const PosedScene& scene, const PinholeCamera& camera,
                                    const ImageFormationOptions& options, const HitShader& shade);

// Per-vertex colours interpolated with the hit's barycentrics.
Color interpolate_vertex_colors(const Scene& scene, const VertexColors& colors, const RayHit& hit);
// The texture coordinates at a hit (the part must have them).
Vec2 interpolate_texcoords(const Scene& scene, const RayHit& hit);
// A layered (textured) part at a hit: the diffuse sum times the texture at
// the interpolated texture coordinates, plus the specular sum.
Color interpolate_layered_colors(const Scene& scene, const VertexColors& colors, const Texture& texture,
                                 const RayHit& hit);
// The texture a layered part is formed with: the colours', else the scene
// material's (null: neither).
const Texture* layer_texture(const Scene& scene, const VertexColors& colors, size_t part);

// Emission (src/core/emission.h) in images: vertex colours include each
// vertex's emission, and a pixel takes the emission at its own texture
// coordinates in place of its vertices' blend of it (docs/design/RENDERER.md
// "Emission"), as base colour textures are taken per pixel.
//
// The emission each part's colours include: the colours' record
// (VertexColors::emission), else the part's scene material's. Throws when a
// textured emission meets a part without texture coordinates.
std::vector<VertexColors::PartEmission> colors_emission(const Scene& scene, const VertexColors& colors);
// Whether any part of `colors` emits.
bool any_emission(const Scene& scene, const VertexColors& colors);
// The colours with that emission taken out of each vertex (what the surfaces reflect).
VertexColors reflected_colors(const Scene& scene, const VertexColors& colors);
// The emission of the part's material at a primary-ray hit (its texture at the
// hit's interpolated texture coordinates): what the per-pixel truth adds.
Color hit_emission(const Scene& scene, const RayHit& hit);

// The image of per-vertex colours (the like-for-like image of a vertex result).
// `colors` must describe `scene`'s parts (checked). A layered (textured) part
// is diffuse × texture(uv) + specular at each sample, the texture sampled at
// the interpolated texture coordinates (Texture::sample). Parts with a shader
// in `part_shaders` take their colour from it; the shader sees what the
// surface reflects (reflected_colors). An emitting part adds its emission at
// each sample, its vertices' emission taken out of the blend.
Image form_image(const PosedScene& scene, const PinholeCamera& camera, const VertexColors& colors,
                 const ImageFormationOptions& options = {}, const PartShaders& part_shaders = {});

// An image drawn with one sample per pixel at S times the size (a
// rasterizer's: its pixel centres are form_image's S×S sample positions)
// as form_image's: each S×S block's RGBA averaged into one pixel.
Image resolve_samples(const Image& fine, int samples_per_side);
// Uncovered shares of an RGBA image (premultiplied) filled with `background`,
// as form_image's opaque_background: alpha becomes 1.
void fill_background(Image& image, const Color& background);
// Uncovered shares of an RGBA image (premultiplied) filled with the
// environment the camera sees there: per pixel, the mean of `environment`
// (nearest texel) over the pixel's S×S sample directions (form_image's), each
// turned into the map's frame by `to_map` (the transpose of the environment's
// rotation). Alpha becomes 1.
void fill_environment_background(Image& image, const PinholeCamera& camera, int samples_per_side,
                                 const CubeMap& environment, const Mat3& to_map);

}  // namespace rsl
