#pragma once
// An RSL set rasterized back into an environment, the error of that
// reconstruction, and the Figure-6-style preview of a fit.
#include <filesystem>

#include "src/lightfit/square_light.h"
#include "src/core/envmap.h"
#include "src/core/image.h"

namespace rsl::lightfit {

// An RSL has no orientation of its own (the runtime aligns it with each
// vertex's frame), so a picture of it needs one.
enum class SquareTurns {
    // One square per light, edges along the local "east" and "north" (the
    // tangent frame whose x is the projection of world +Y): what the preview shows.
    kAligned,
    // The mean over the fit's turns θ ∈ {0, π/8, π/4, 3π/8}: what the fit
    // objective compares against; used for error measurement.
    kAveraged,
};

// 6×n×n cube map whose texel k holds Σ_i I_i · (fraction of texel k inside
// light i's square), the fraction estimated with supersampling² subsamples
// weighted by their solid angle.
CubeMap reconstruct(const RslSet& set, int n, SquareTurns turns = SquareTurns::kAveraged, int supersampling = 4);

// ‖a − b‖ / ‖a‖ over the sphere (texel solid angles, RGB), same resolution.
double relative_l2_error(const CubeMap& reference, const CubeMap& approximation);

// Three lat-long panels side by side, like the RSL paper's Figure 6: the map,
// the map with region boundaries drawn in green, the RSL reconstruction. One
// exposure for all panels (99th luminance percentile of the map → 0.9).
Image fit_preview(const CubeMap& map, const RslSet& set, int panel_width = 512);

}  // namespace rsl::lightfit
