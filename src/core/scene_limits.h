#pragma once
// Limits of what a scene may hold beyond its file's syntax (docs/SCENE_FORMAT.md):
// values the loader accepts one by one but whose results no file can hold.
#include <filesystem>
#include <string>

#include "src/core/scene.h"

namespace rsl {

// The brightest lights a scene may hold, per channel: far past any real lamp
// or sun, and low enough that every result stays within what an image file
// holds (kMaxRadiance, src/formats/image_file.h) instead of overflowing to Inf and NaN.
inline constexpr float kMaxLightPower = 1e12f;     // W
inline constexpr float kMaxLightRadiance = 1e13f;  // power / (4π² radius²)
inline constexpr float kMaxSunIrradiance = 1e12f;  // a glTF sun's intensity × colour
// A material's emission per channel (radiance: emissive × emissive strength).
inline constexpr float kMaxEmission = 1e13f;

// What is wrong with a light against the limits above, as a key's tail
// (".power: 3e+38 W is past the limit; …"), or empty.
std::string light_limit_problem(const LocalLight& light);
// Throws rsl::Error naming `path` (the scene's file) and the light unless
// every local light and sun is within the limits above.
void check_light_limits(const Scene& scene, const std::filesystem::path& path);

// Images: a side of a scene's camera, `rsl render`'s and `rsl truth`'s
// --width and --height, and the API's; S×S primary rays per pixel (16: 256,
// far past where an image stops changing).
inline constexpr int kMaxImageSide = 16384;
inline constexpr int kMaxPixelSamplesPerSide = 16;

// Throws rsl::Error naming `path` and the part unless every part's
// part-to-world transform at the scene's start is invertible (finite,
// |det| ≥ kMinTransformDeterminant, as the ray scene requires): a zero or
// huge scale in a glTF node otherwise fails in the ray scene, after the fit
// and the bake, without the part's name.
inline constexpr float kMinTransformDeterminant = 1e-20f;
bool invertible_transform(const Mat4& part_to_world);
void check_part_transforms(const Scene& scene, const std::filesystem::path& path);
// The same check for a frame posed at time t (an animated scale may reach 0
// after the start): throws naming the scene's file, the part and t.
void check_part_pose(const Scene& scene, int part, float t, const Mat4& part_to_world);

}  // namespace rsl
