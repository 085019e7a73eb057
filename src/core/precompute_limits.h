#pragma once
// The limits of a scene's "precompute" settings (docs/SCENE_FORMAT.md), one
// set of rules for the scene file and for `rsl bake`'s flags: a value past
// them is a typo, sizes buffers that would not fit, or bakes a field file
// the reader refuses (so every later run would bake it again).
#include <optional>
#include <string>

#include "src/core/scene.h"

namespace rsl {

struct PrecomputeLimit {
    const char* key;  // under "precompute", as the scene file spells it: "svdf.vectors"
    int least, most;
};

inline constexpr PrecomputeLimit kSvdfResolutionLimit{"svdf.resolution", 2, 256};
inline constexpr PrecomputeLimit kSvdfClustersLimit{"svdf.clusters", 1, 65536};
inline constexpr PrecomputeLimit kSvdfVectorsLimit{"svdf.vectors", 1, 256};
inline constexpr PrecomputeLimit kSvdfSupersamplingLimit{"svdf.supersampling", 1, 32};
// Below 2 shells or 2 samples a side, the lookups have no second tap.
inline constexpr PrecomputeLimit kOvdfShellsLimit{"ovdf.shells", 2, 256};
inline constexpr PrecomputeLimit kOvdfCubeResolutionLimit{"ovdf.cube_resolution", 2, 256};
inline constexpr PrecomputeLimit kOvdfVdtResolutionLimit{"ovdf.vdt_resolution", 2, 256};
inline constexpr PrecomputeLimit kOvdfVectorsLimit{"ovdf.vectors", 1, 256};

// "must be an integer from 1 to 256, got 1025"; empty when within the limit.
std::string limit_problem(const PrecomputeLimit& limit, long long value);

struct PrecomputeProblem {
    std::string key;      // "ovdf.cube_resolution"
    std::string message;  // "must be even"
};

// The first setting that breaks a rule (every integer within its limit; the
// cube resolution even; the outer radius beyond the inner), or none.
std::optional<PrecomputeProblem> precompute_problem(const PrecomputeSettings& settings);

}  // namespace rsl
