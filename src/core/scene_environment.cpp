#include "src/core/scene_environment.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "src/core/error.h"
#include "src/core/image.h"

namespace rsl {

void add_sun(CubeMap& map, const Vec3& towards_sun, const Color& irradiance) {
    RSL_CHECK_GT(map.texel_count(), 0);
    // One texel, not a splat over its neighbours: the fit then finds the sun
    // as the smallest square the map allows (a texel: 3.6° at N = 32).
    const int texel = map.index_of(towards_sun);
    map.radiance(texel) += irradiance / map.solid_angle(texel);
}

std::string describe_environment(const EnvironmentDesc& env) {
    std::vector<std::string> what;
    if (!env.file.empty()) what.push_back(env.file.filename().string());
    if (env.uniform != Color(0))
        what.push_back(env.uniform == Color(env.uniform.r)
                           ? fmt::format("a uniform sky of radiance {:g}", env.uniform.r)
                           : fmt::format("a uniform sky of radiance ({:g}, {:g}, {:g})", env.uniform.r, env.uniform.g,
                                         env.uniform.b));
    for (const SunLight& sun : env.suns) what.push_back(fmt::format("sun '{}'", sun.name));
    return what.empty() ? "none" : fmt::format("{}", fmt::join(what, " + "));
}

CubeMap scene_environment_map(const Scene& scene, int resolution, bool second) {
    const EnvironmentDesc& env = scene.environment;
    const std::filesystem::path& file = second ? env.second_file : env.file;
    CubeMap map = file.empty() ? CubeMap(resolution) : load_environment(file, resolution);
    if (env.uniform != Color(0))
        for (Color& radiance : map.radiances()) radiance += env.uniform;
    // The map's own frame: content at map direction m shows at rotation_at(t)·m.
    const float start = scene.animation.start;
    const Mat3 to_map = glm::transpose(env.rotation_at(start));
    for (const SunLight& sun : env.suns) {
        const Vec3 towards = to_map * sun.direction_at(scene, start);
        // Refused here, by name, rather than by the fit as a texel's radiance.
        const float brightest = std::max({sun.irradiance.r, sun.irradiance.g, sun.irradiance.b});
        const float radiance = brightest / map.solid_angle(map.index_of(towards));
        if (!(radiance <= kMaxRadiance))
            throw_file_error(scene.source, "sun '{}': irradiance {:g} is radiance {:g} in one texel of the {}² cube "
                             "map, above the {:g} rsl accepts (lower the light's intensity)",
                             sun.name, brightest, radiance, resolution, kMaxRadiance);
        add_sun(map, towards, sun.irradiance);
    }
    return map;
}

}  // namespace rsl
