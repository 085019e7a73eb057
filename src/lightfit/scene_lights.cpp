#include "src/lightfit/scene_lights.h"

#include <cmath>

#include "src/lightfit/decompose.h"
#include "src/lightfit/irradiance.h"
#include "src/formats/scene_environment.h"

namespace rsl {

RslSet fit_environment_lights(const CubeMap& environment, int lights, bool cross_face) {
    if (environment.energy() == DVec3(0.0)) {  // a black map (a scene lit by suns alone): nothing to fit
        RslSet none;
        none.resolution = environment.resolution();
        return none;
    }
    lightfit::DecomposeOptions options;
    options.lights = lights;
    options.cross_face = cross_face;
    RslSet set = lightfit::decompose(environment, options);
    set.irradiance = std::make_shared<const IrradianceMap>(irradiance_map(environment));
    return set;
}

RslSet fit_scene_lights(const Scene& scene, const CubeMap& environment, int lights, bool cross_face) {
    RslSet set = fit_environment_lights(environment, lights, cross_face);
    const std::vector<RotatableSquareLight> suns = sun_lights(scene);
    set.lights.insert(set.lights.end(), suns.begin(), suns.end());
    if (!suns.empty()) {  // the suns' irradiance joins the map's (a black map has none yet)
        IrradianceMap irradiance = set.irradiance ? *set.irradiance : irradiance_map(environment);
        for (const RotatableSquareLight& sun : suns)
            add_directional_irradiance(irradiance, sun.center, Color(sun.light_integral()));
        set.irradiance = std::make_shared<const IrradianceMap>(std::move(irradiance));
    }
    return set;
}

std::vector<RotatableSquareLight> sun_lights(const Scene& scene) {
    const float half_diagonal = kSunAngularRadius * std::sqrt(0.5f * kPi);  // 2r² = π·α²
    std::vector<RotatableSquareLight> lights;
    for (const SunLight& sun : scene.environment.suns) {
        RotatableSquareLight light;
        light.center = sun_direction_in_map(scene, sun);
        light.half_diagonal = half_diagonal;
        light.radiance = sun.irradiance / light.solid_angle();
        lights.push_back(light);
    }
    return lights;
}

}  // namespace rsl
