#include "src/core/scene_limits.h"

#include <algorithm>
#include <cmath>

#include "src/core/error.h"

namespace rsl {

std::string light_limit_problem(const LocalLight& light) {
    const float most = std::max({light.power.r, light.power.g, light.power.b});
    const float least = std::min({light.power.r, light.power.g, light.power.b});
    if (!(most <= kMaxLightPower && least >= 0))
        return fmt::format(".power: {:g} W is past the limit; expected 0 to {:g} W per channel",
                           most <= kMaxLightPower ? least : most, kMaxLightPower);
    if (!(light.radius > 0)) return fmt::format(".radius: {:g}, expected a positive radius", light.radius);
    const double radiance = double(most) / (4.0 * kPi * kPi * double(light.radius) * double(light.radius));
    if (!(radiance <= double(kMaxLightRadiance)))
        return fmt::format(": radiance power / (4π² radius²) = {:g} (power {:g} W, radius {:g}) is past the limit "
                           "{:g}; give a larger radius or a smaller power", radiance, most, light.radius,
                           kMaxLightRadiance);
    return "";
}

// Checked where the scene loads: minutes of work would otherwise end in Inf and NaN pixels.
void check_light_limits(const Scene& scene, const std::filesystem::path& path) {
    size_t scene_file_light = 0;
    for (const LocalLight& light : scene.lights) {
        const std::string where = light.name.empty() ? fmt::format("lights[{}]", scene_file_light++)
                                                     : fmt::format("glTF light '{}'", light.name);
        if (const std::string problem = light_limit_problem(light); !problem.empty())
            throw_file_error(path, "{}{}", where, problem);
    }
    for (const SunLight& sun : scene.environment.suns) {
        const float most = std::max({sun.irradiance.r, sun.irradiance.g, sun.irradiance.b});
        if (!(most <= kMaxSunIrradiance))
            throw_file_error(path, "glTF sun '{}': irradiance (intensity × colour) {:g} is past the limit; expected 0 "
                             "to {:g}", sun.name, most, kMaxSunIrradiance);
    }
}

bool invertible_transform(const Mat4& part_to_world) {
    const float det = glm::determinant(Mat3(part_to_world));
    return std::isfinite(det) && std::abs(det) >= kMinTransformDeterminant;
}

// At the start only: a glTF may key a scale to 0 to hide a part for a while,
// and a frame posed there is refused when it is posed (check_part_pose).
void check_part_transforms(const Scene& scene, const std::filesystem::path& path) {
    for (const Part& part : scene.parts) {
        const Mat4 m = scene.node_world_at(part.node, scene.animation.start);
        if (!invertible_transform(m))
            throw_file_error(path, "part '{}': its transform at the scene's start (t = {:g} s) is singular "
                             "(determinant {:g}; a zero or huge scale?), so the part has no shape to render",
                             part.name, scene.animation.start, glm::determinant(Mat3(m)));
    }
}

void check_part_pose(const Scene& scene, int part, float t, const Mat4& part_to_world) {
    if (invertible_transform(part_to_world)) return;
    throw_file_error(scene.source, "part '{}': its transform at t = {:g} s is singular (determinant {:g}; an "
                     "animated scale reaching 0?), so the part has no shape to render at that time",
                     scene.parts[size_t(part)].name, t, glm::determinant(Mat3(part_to_world)));
}

}  // namespace rsl
