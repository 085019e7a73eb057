#include "src/formats/scene_environment.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "src/core/error.h"
#include "src/formats/environment_file.h"

namespace rsl {

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

CubeMap scene_environment_at(const Scene& scene, int resolution, float t) {
    const CubeMap first = scene_environment_map(scene, resolution);  // black without one: lights only
    if (scene.environment.second_file.empty()) return first;
    return blend_environments(first, scene_environment_map(scene, resolution, true), scene.environment.blend_weight_at(t));
}

Vec3 sun_direction_in_map(const Scene& scene, const SunLight& sun) {
    const float start = scene.animation.start;
    return glm::transpose(scene.environment.rotation_at(start)) * sun.direction_at(scene, start);
}

CubeMap scene_environment_map(const Scene& scene, int resolution, bool second) {
    const EnvironmentDesc& env = scene.environment;
    const std::filesystem::path& file = second ? env.second_file : env.file;
    CubeMap map;
    try {
        map = file.empty() ? CubeMap(resolution) : load_environment(file, resolution);
    } catch (const Error& e) {
        // As a mesh's errors: the scene file and the key first, then the map's own error.
        if (scene.source.empty()) throw;
        throw_file_error(scene.source, "{}: {}", second ? "environment.second_file" : "environment.file", e.what());
    }
    if (env.uniform != Color(0))
        for (Color& radiance : map.radiances()) radiance += env.uniform;
    return map;
}

}  // namespace rsl
