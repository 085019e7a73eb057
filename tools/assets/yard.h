#pragma once
// The yard: a scene family for scale, N rigid instances of four small meshes
// (a crate, a cup, a spinning top and a ring, ~500 vertices each) on a
// ground sheet. Each instance bounces, tumbles or orbits with its own phase
// in a 4-second loop, so the occluder culling sees real motion. The density
// stays the same as N grows (one instance per square metre), so a part has
// about as many neighbours within reach at N = 8 as at N = 1,024.
#include <filesystem>
#include <string>

#include "tools/assets/model.h"

namespace rsl::assets {

inline constexpr float kYardLoopSeconds = 4.0f;
inline constexpr int kYardMaxInstances = 4096;
// The OVDF's outer radius, in bounding radii. Measured with `rsl bench
// scale --reaches` (docs/journal/results-history.md "The reach, once more"): the ground's
// long shadows need the reach (the all-vertex error's growth from N = 8 to
// 64: +1.04 points at 10R, +0.89 at 16R, +0.81 at 20R), and each step costs
// frame time (yard-128 at 16R about 1.1x the 10R frame); 6 and 4 cut the
// shadows on the ground outright (error 4.2% → 6.9%, 11.8% on yard-32).
inline constexpr double kYardOvdfReach = 16.0;

// Nodes: "ground" (static), then "crate_0000", "cup_0001", ... (one per
// instance, meshes shared: instance i uses mesh i mod 4).
GeneratedModel make_yard(int instances);

// Writes yard-N.glb and the scene file yard-N.json beside it (the bench
// field settings; `environment` is the map's path as the scene file names
// it, relative to `dir`) and returns the scene file's path. Throws
// rsl::Error for N outside [1, kYardMaxInstances].
std::filesystem::path write_yard(const std::filesystem::path& dir, int instances,
                                 const std::string& environment = "sunsky.exr");

}  // namespace rsl::assets
