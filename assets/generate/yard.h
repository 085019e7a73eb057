#pragma once
// The yard: a scene family for scale, N rigid instances of four small meshes
// (a crate, a cup, a spinning top and a ring, ~500 vertices each) on a
// ground sheet. Each instance bounces, tumbles or orbits with its own phase
// in a 4-second loop, so the occluder culling sees real motion. The density
// stays the same as N grows (one instance per square metre), so a part has
// about as many neighbours within reach at N = 8 as at N = 1,024.
#include <filesystem>
#include <string>

#include "assets/generate/model.h"

namespace rsl::assets {

inline constexpr float kYardLoopSeconds = 4.0f;
inline constexpr int kYardMaxInstances = 4096;

// Nodes: "ground" (static), then "crate_0000", "cup_0001", ... (one per
// instance, meshes shared: instance i uses mesh i mod 4).
GeneratedModel make_yard(int instances);

// Writes yard-N.glb and the scene file yard-N.json beside it (environment
// sunsky.exr from the same folder; the bench field settings) and returns the
// scene file's path. Throws rsl::Error for N outside [1, kYardMaxInstances].
std::filesystem::path write_yard(const std::filesystem::path& dir, int instances);

}  // namespace rsl::assets
