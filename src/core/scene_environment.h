#pragma once
// What lights a scene from afar, as one cube map: its environment file (or a
// black map), plus a uniform sky, plus its suns. Every consumer — the RSL fit
// behind both renderers, `rsl truth`, the viewer — takes the scene's
// environment from here, so a glTF sun lights them all alike.
#include <string>

#include "src/core/envmap.h"
#include "src/core/scene.h"

namespace rsl {

// The scene's environment map at cube resolution N (the renderers take
// environment.resolution; the truth its own):
// environment.file (second: environment.second_file, the blend's other end),
// `uniform` added to every texel, and each sun's irradiance E added to the
// texel around its direction at the scene's start as radiance E / Ω (the
// texel's solid angle), so that the map's energy grows by exactly E. Both
// ends of a blend get the suns, so the blend keeps them whole. The map turns
// with environment.rotation; a sun is placed where it stands at the start.
CubeMap scene_environment_map(const Scene& scene, int resolution, bool second = false);

// What lights the scene from afar, for messages: "grace.hdr", "a uniform sky
// of radiance 1", "grace.hdr + sun 'Sun'", or "none".
std::string describe_environment(const EnvironmentDesc& environment);

// Adds a sun of irradiance E (per channel) in unit direction `towards_sun`
// to the map (as above).
void add_sun(CubeMap& map, const Vec3& towards_sun, const Color& irradiance);

}  // namespace rsl
