#pragma once
// Bottom-up decomposition of a cube map into K regions, each fitted with a
// rotatable square light (RSL paper §4.1.2).
//
// Every texel starts as its own region. Each step merges the adjacent pair
// whose merge is cheapest. The paper recomputes every pair at every step
// (O(m²) per step, ~2 minutes for 6×32×32); here the candidate pairs live in a
// priority queue, a merge re-fits only the pairs of the merged region, and
// entries made stale by a merge are recognised by version stamps when popped
// and dropped (lazy invalidation). Region statistics add up, texel lists are
// appended smaller-into-larger, so the whole merge is near-linear in texels.
#include "src/lightfit/square_light.h"
#include "src/lightfit/square_fit.h"
#include "src/core/envmap.h"

namespace rsl::lightfit {

// What "cheapest merge" means.
enum class MergeCost {
    // The merged region's fit error (the paper's rule: "the merged subregion
    // has the least RSL fitting error").
    kMergedError,
    // How much the merge raises the sum of fit errors (greedy descent on the
    // paper's global objective, Ward's rule in clustering terms).
    kErrorIncrease,
};

struct DecomposeOptions {
    int lights = 30;           // stop at this many regions
    // > 0: stop earlier, before the first merge whose merged region's fit
    // error (relative to |map energy|²) would exceed it. The count of lights is
    // then driven by the error; `lights` stays a lower bound.
    double max_error = 0;
    bool cross_face = true;    // merge across cube-face borders (the paper: same face only)
    MergeCost cost = MergeCost::kErrorIncrease;  // lower reconstruction error on the probes (docs/design/LIGHTFIT.md)
    FitOptions merge_fit{.refine_center = false};  // fits that rank candidate merges
    FitOptions final_fit{};                        // the fits of the final regions
};

// The RSL set of `map`, with region labels. Fewer merges than asked for happen
// only when no adjacent pair is left (same-face merging stops at 6 regions);
// the result then has more lights than options.lights.
RslSet decompose(const CubeMap& map, const DecomposeOptions& options);

}  // namespace rsl::lightfit
