#include "src/trace/image_formation.h"

#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"

namespace rsl {

PinholeCamera PinholeCamera::at_time(const Camera& camera, float t, int width, int height) {
    if (width <= 0 || height <= 0) throw_error("camera: image size {}×{} is empty", width, height);
    if (!(camera.fov_y_degrees > 0.0f && camera.fov_y_degrees < 180.0f))
        throw_error("camera: vertical field of view {}° is not in (0°, 180°)", camera.fov_y_degrees);
    PinholeCamera c;
    c.eye = camera.position_at(t);
    const Vec3 view = camera.target_at(t) - c.eye;
    if (!(glm::length(view) > 0.0f)) throw_error("camera: position and target coincide at t = {}", t);
    c.forward = glm::normalize(view);
    Vec3 right = glm::cross(c.forward, camera.up);
    if (!(glm::length(right) > 1e-6f)) right = any_orthonormal(c.forward);  // looking along `up`
    c.right = glm::normalize(right);
    c.up = glm::cross(c.right, c.forward);
    c.tan_half_fov_y = std::tan(0.5f * glm::radians(camera.fov_y_degrees));
    c.width = width;
    c.height = height;
    return c;
}

Vec3 PinholeCamera::direction(float px, float py) const {
    const float aspect = float(width) / float(height);
    const float sx = (2.0f * px / float(width) - 1.0f) * tan_half_fov_y * aspect;
    const float sy = (1.0f - 2.0f * py / float(height)) * tan_half_fov_y;
    return glm::normalize(forward + sx * right + sy * up);
}

Image trace_image(const PosedScene& scene, const PinholeCamera& camera, const ImageFormationOptions& options,
                  const HitShader& shade, const ProgressCallback& progress) {
    RSL_CHECK_GE(options.samples_per_side, 1);
    const int s = options.samples_per_side;
    const float inv_samples = 1.0f / float(s * s);
    Image image(camera.width, camera.height, 4);
    std::atomic<size_t> rows_done{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, camera.height, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            for (int x = 0; x < camera.width; ++x) {
                Color sum(0);
                int covered = 0;
                for (int b = 0; b < s; ++b)
                    for (int a = 0; a < s; ++a) {
                        const Vec3 dir = camera.direction(float(x) + (float(a) + 0.5f) / float(s),
                                                          float(y) + (float(b) + 0.5f) / float(s));
                        const RayHit hit = scene.rays().intersect(camera.eye, dir);
                        if (hit.hit) {
                            sum += shade(hit, dir);
                            ++covered;
                        } else if (options.opaque_background) {
                            sum += options.background;
                        }
                    }
                float* pixel = image.at(x, y);
                pixel[0] = sum.r * inv_samples;
                pixel[1] = sum.g * inv_samples;
                pixel[2] = sum.b * inv_samples;
                pixel[3] = options.opaque_background ? 1.0f : float(covered) * inv_samples;
            }
        }
        const size_t done = rows_done.fetch_add(rows.size()) + rows.size();
        if (progress) progress(done * size_t(camera.width), size_t(camera.height) * camera.width);
    });
    return image;
}

Color interpolate_vertex_colors(const Scene& scene, const VertexColors& colors, const RayHit& hit) {
    const TriangleMesh& mesh = scene.parts[hit.instance].mesh;
    const std::vector<Color>& part = colors.parts[hit.instance];
    const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
    return (1.0f - hit.u - hit.v) * part[tri[0]] + hit.u * part[tri[1]] + hit.v * part[tri[2]];
}

Image form_image(const PosedScene& scene, const PinholeCamera& camera, const VertexColors& colors,
                 const ImageFormationOptions& options) {
    const Scene& s = scene.scene();
    if (colors.parts.size() != s.parts.size())
        throw_error("vertex colours of '{}' have {} parts, scene '{}' has {}", colors.scene_name,
                    colors.parts.size(), s.name, s.parts.size());
    for (size_t p = 0; p < s.parts.size(); ++p)
        if (colors.parts[p].size() != s.parts[p].mesh.vertex_count())
            throw_error("vertex colours of '{}': part '{}' has {} values for {} vertices", colors.scene_name,
                        s.parts[p].name, colors.parts[p].size(), s.parts[p].mesh.vertex_count());
    return trace_image(scene, camera, options, [&](const RayHit& hit, const Vec3&) {
        return interpolate_vertex_colors(s, colors, hit);
    });
}

}  // namespace rsl
