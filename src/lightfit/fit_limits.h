#pragma once
// What a cube map and its fitted lights cannot show, measured on them
// (docs/design/LIGHTFIT.md "Limits a fit reports"): a source no wider than
// a texel or two, whose shadows come out as soft as the texels, and a light whose
// square is much wider than the bright source that gives most of its light,
// whose shadows come out as soft as the square.
#include <cstddef>
#include <string>

#include "src/core/envmap.h"
#include "src/lightfit/square_light.h"

namespace rsl {

// A point-like source: the brightest texel and the texels joined to it
// above a tenth of its radiance, when they are at most kPointLikeTexels (a
// source smaller than a texel that straddles their edges lights 2×2) and
// carry at least kPointLikeShare of the map's light.
inline constexpr size_t kPointLikeTexels = 4;
inline constexpr double kPointLikeShare = 0.1;

struct PointLikeSource {
    bool found = false;
    int texel = -1;
    double share = 0;            // of the map's luminance-weighted light
    double texel_degrees = 0;    // the texels' width, √Ω
};
PointLikeSource find_point_like_source(const CubeMap& map);

// A crowded light: one square standing for a region whose light it cannot
// hold. Too soft: the region holds at least kCrowdedShare of the map's
// light, most of it (kCrowdedConcentration) from texels that cover at most
// 1/kCrowdedSpread of the square. Too hard: at least kMisplacedShare of the
// map's light lies in the region outside the square's circumscribed cone
// (a bright source drew the square to it and the rest of the region's light
// with it).
inline constexpr double kCrowdedShare = 0.05;
inline constexpr double kCrowdedConcentration = 0.5;
inline constexpr double kCrowdedSpread = 8.0;
inline constexpr double kMisplacedShare = 0.1;

struct CrowdedLight {
    bool found = false;
    bool too_hard = false;      // false: too soft
    int light = -1;
    double share = 0;           // of the map's light: the region's (too soft) or the misplaced part (too hard)
    double light_degrees = 0;   // the square's width, √Ω
    double source_degrees = 0;  // the bright texels' width, √Ω
};
// The set's region labels must describe `map` (RslSet::region_of_texel);
// without them nothing is found.
CrowdedLight find_crowded_light(const CubeMap& map, const RslSet& set);

// The user-facing sentences: "" when nothing was found. `name` names the map.
std::string point_like_note(const std::string& name, const CubeMap& map, const PointLikeSource& source);
std::string crowded_light_warning(const std::string& name, int lights, const CrowdedLight& crowded);

}  // namespace rsl
