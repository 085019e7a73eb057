#pragma once
// A scene's environment lights: its map fitted with K rotatable square
// lights (decompose.h), and one light of the sun's own size per glTF sun
// (docs/design/LIGHTFIT.md). What every renderer, the viewer and the API
// start from.
#include <vector>

#include "src/lightfit/square_light.h"
#include "src/core/envmap.h"
#include "src/core/scene.h"

namespace rsl {

// The environment map fitted with K RSLs (lightfit, default options); none
// for a black map.
RslSet fit_environment_lights(const CubeMap& environment, int lights, bool cross_face = true);

// The sun's angular radius (0.267°): a glTF sun is a square of the sun's
// solid angle, 2r² = π·α², so that its shadows are as hard as the sun's.
inline constexpr float kSunAngularRadius = 0.00465f;
// The scene's environment lights: its map (scene_environment_map) fitted with
// K RSLs, then one RSL per sun — centred on the sun's direction in the map's
// frame at the scene's start (it turns with environment.rotation), of the
// sun's solid angle, its integral 2r²·I the sun's irradiance E. The ground
// truth takes the same suns as directions of irradiance E (GroundTruth).
RslSet fit_scene_lights(const Scene& scene, const CubeMap& environment, int lights, bool cross_face = true);
// The suns' lights alone (what fit_scene_lights appends to the map's).
std::vector<RotatableSquareLight> sun_lights(const Scene& scene);

}  // namespace rsl
