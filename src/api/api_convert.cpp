#include "src/api/api_convert.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <mutex>

#include "src/core/scene_limits.h"

namespace rsl::api {

std::vector<std::string> input_files(const ::rsl::Scene& scene) {
    std::vector<std::string> files;
    for (const std::filesystem::path& file : scene.input_files) files.push_back(file.string());
    for (const std::filesystem::path& map : {scene.environment.file, scene.environment.second_file})
        if (!map.empty()) files.push_back(map.string());
    return files;
}

Transform to_transform(const Pose& pose, const std::string& what) {
    Transform t;
    t.translation = finite_vec3(pose.translation, what + " translation");
    t.scale = finite_vec3(pose.scale, what + " scale");
    // As a scene file's "scale": a mirrored part would turn its faces inside out.
    if (!(t.scale.x > 0 && t.scale.y > 0 && t.scale.z > 0))
        throw_error("{} scale: ({}, {}, {}) must be positive", what, t.scale.x, t.scale.y, t.scale.z);
    const auto& q = pose.rotation;
    const Quat rotation(q[0], q[1], q[2], q[3]);  // glm: (w, x, y, z)
    const float norm = glm::length(rotation);
    if (!std::isfinite(norm) || norm < 1e-6f)
        throw_error("{} rotation: quaternion ({}, {}, {}, {}) is not a rotation", what, q[0], q[1], q[2], q[3]);
    t.rotation = rotation;  // Transform::matrix() normalizes it, as it does a file's
    // As a scene file's part: the ray scene cannot invert a scale of 1e20 (det Inf) or 1e-30 (det 0).
    if (!invertible_transform(t.matrix()))
        throw_error("{} scale: ({:g}, {:g}, {:g}) makes a singular transform (determinant {:g}); expected a product of "
                    "the scales from {:g} to {:g}", what, t.scale.x, t.scale.y, t.scale.z,
                    double(t.scale.x) * t.scale.y * t.scale.z, kMinTransformDeterminant,
                    std::numeric_limits<float>::max());
    return t;
}

void set_rotation(EnvironmentDesc& environment, const Float3& axis, float degrees, float degrees_per_second) {
    const Vec3 a = finite_vec3(axis, "environment rotation axis");
    if (glm::length(a) == 0) throw_error("environment rotation axis: (0, 0, 0) is no axis");
    if (!std::isfinite(degrees) || !std::isfinite(degrees_per_second))
        throw_error("environment rotation: {} degrees, {} per second: expected finite numbers", degrees,
                    degrees_per_second);
    environment.rotation_axis = glm::normalize(a);
    environment.rotation_degrees = degrees;
    environment.rotation_degrees_per_second = degrees_per_second;
}

::rsl::Camera to_camera(const Camera& c) {
    ::rsl::Camera camera;
    camera.position = finite_vec3(c.position, "camera position");
    camera.target = finite_vec3(c.target, "camera target");
    camera.up = finite_vec3(c.up, "camera up");
    if (glm::length(camera.target - camera.position) <= 0) throw_error("camera: the target is the position");
    if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180))
        throw_error("camera fov_y_degrees {}: expected between 0 and 180", c.fov_y_degrees);
    if (c.width < 1 || c.height < 1) throw_error("camera size {}×{}: expected at least 1×1", c.width, c.height);
    camera.fov_y_degrees = c.fov_y_degrees;
    camera.width = c.width, camera.height = c.height;
    return camera;
}

LocalLight to_local_light(const SphereLight& l) {
    LocalLight light;
    light.position = finite_vec3(l.position, "sphere light position");
    light.power = finite_vec3(l.power, "sphere light power");
    light.radius = l.radius;
    return light;  // the renderer checks the radius (VertexRenderer::check_local_lights)
}

SphereLight to_sphere_light(const LocalLight& l) { return {to_float3(l.position), l.radius, to_float3(l.power)}; }

VertexColors to_api(const ::rsl::VertexColors& layered) {
    // The API's colours have no layers: textured parts at unit texture (docs/design/RENDERER.md).
    const ::rsl::VertexColors colors = layered.at_unit_texture();
    VertexColors out;
    out.part_names = colors.part_names;
    out.time = colors.time;
    out.scene_name = colors.scene_name, out.producer = colors.producer;
    out.part_offsets.push_back(0);
    out.rgb.reserve(3 * colors.vertex_count());
    for (const std::vector<Color>& part : colors.parts) {
        for (const Color& c : part) out.rgb.insert(out.rgb.end(), {c.r, c.g, c.b});
        out.part_offsets.push_back(out.part_offsets.back() + part.size());
    }
    return out;
}

::rsl::VertexColors to_internal(const VertexColors& colors, const std::string& what) {
    const auto& offsets = colors.part_offsets;
    if (offsets.size() != colors.part_names.size() + 1 || offsets.front() != 0 ||
        !std::is_sorted(offsets.begin(), offsets.end()) || colors.rgb.size() != 3 * offsets.back())
        throw_error("{}: part_offsets ({} entries, last {}) do not fit {} parts and {} colour values", what,
                    offsets.size(), offsets.empty() ? 0 : offsets.back(), colors.part_names.size(), colors.rgb.size());
    ::rsl::VertexColors out;
    out.scene_name = colors.scene_name, out.producer = colors.producer;
    out.time = colors.time;
    for (size_t p = 0; p < colors.part_names.size(); ++p) {
        out.add_part(colors.part_names[p], offsets[p + 1] - offsets[p]);
        for (size_t v = offsets[p]; v < offsets[p + 1]; ++v)
            out.parts[p][v - offsets[p]] = Color(colors.rgb[3 * v], colors.rgb[3 * v + 1], colors.rgb[3 * v + 2]);
    }
    return out;
}

Image to_api(const ::rsl::Image& image) {
    Image out;
    out.width = image.width, out.height = image.height;
    out.rgba.resize(size_t(image.width) * image.height * 4, 1.0f);
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
        for (int c = 0; c < image.channels; ++c) out.rgba[4 * i + c] = image.pixels[i * image.channels + c];
    return out;
}

::rsl::Image to_internal(const Image& image, const std::string& what) {
    if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * image.height * 4)
        throw_error("{}: {} values for a {}×{} RGBA image", what, image.rgba.size(), image.width, image.height);
    ::rsl::Image out(image.width, image.height, 4);
    out.pixels = image.rgba;
    return out;
}

Progress throttled(Progress progress) {
    if (!progress) return {};
    struct Gate {
        std::mutex mutex;
        std::string step;
        std::chrono::steady_clock::time_point last{};
    };
    auto gate = std::make_shared<Gate>();
    return [progress = std::move(progress), gate](const std::string& step, double fraction) {
        std::lock_guard<std::mutex> lock(gate->mutex);
        const auto now = std::chrono::steady_clock::now();
        if (fraction < 1.0 && step == gate->step && now - gate->last < std::chrono::milliseconds(100)) return;
        gate->step = step, gate->last = now;
        progress(step, std::clamp(fraction, 0.0, 1.0));
    };
}

}  // namespace rsl::api
