#pragma once
// What lights a scene from afar: its environment file (or a black map) plus a
// uniform sky, as one cube map, and its suns. Every consumer — the RSL fit
// behind both renderers, `rsl truth`, the viewer — takes the scene's
// environment from here.
#include <string>

#include "src/core/envmap.h"
#include "src/core/scene.h"

namespace rsl {

// The scene's environment map at cube resolution N (the renderers take
// environment.resolution; the truth its own): environment.file (second:
// environment.second_file, the blend's other end), or a black map, with
// `uniform` added to every texel. The suns are not in it: a texel is far
// wider than the sun, so each is a light of its own (fit_scene_lights,
// src/render/cpu_renderer.h) and a direction of the ground truth.
CubeMap scene_environment_map(const Scene& scene, int resolution, bool second = false);
// The environment at time t: with environment.second_file, the blend
// (1 − w)·first + w·second (EnvironmentDesc::blend_weight_at), which the RSL
// renderer applies to its two RSL sets; else the first map.
CubeMap scene_environment_at(const Scene& scene, int resolution, float t);

// A sun's direction in the environment map's frame: where it stands at the
// scene's start, turned back by environment.rotation there (content at map
// direction m shows at rotation_at(t)·m), so it turns with the map.
Vec3 sun_direction_in_map(const Scene& scene, const SunLight& sun);

// What lights the scene from afar, for messages: "grace.hdr", "a uniform sky
// of radiance 1", "grace.hdr + sun 'Sun'", or "none".
std::string describe_environment(const EnvironmentDesc& environment);

}  // namespace rsl
