#include "src/core/precompute_limits.h"

#include <fmt/format.h>

namespace rsl {

std::string limit_problem(const PrecomputeLimit& limit, long long value) {
    if (value >= limit.least && value <= limit.most) return "";
    return fmt::format("must be an integer from {} to {}, got {}", limit.least, limit.most, value);
}

std::optional<PrecomputeProblem> precompute_problem(const PrecomputeSettings& s) {
    const std::pair<const PrecomputeLimit*, int> integers[] = {
        {&kSvdfResolutionLimit, s.svdf_resolution},   {&kSvdfClustersLimit, s.svdf_clusters},
        {&kSvdfVectorsLimit, s.svdf_vectors},         {&kSvdfSupersamplingLimit, s.svdf_supersampling},
        {&kOvdfShellsLimit, s.ovdf_shells},           {&kOvdfCubeResolutionLimit, s.ovdf_cube_resolution},
        {&kOvdfVdtResolutionLimit, s.ovdf_vdt_resolution}, {&kOvdfVectorsLimit, s.ovdf_vectors}};
    for (const auto& [limit, value] : integers)
        if (std::string problem = limit_problem(*limit, value); !problem.empty())
            return PrecomputeProblem{limit->key, std::move(problem)};
    // Each face is split into 2 × 2 segments (OvdfParams::segments_per_side).
    if (s.ovdf_cube_resolution % 2 != 0)
        return PrecomputeProblem{"ovdf.cube_resolution", fmt::format("must be even, got {}", s.ovdf_cube_resolution)};
    if (!(s.ovdf_outer_radius > s.ovdf_inner_radius))
        return PrecomputeProblem{"ovdf.outer_radius", "must be larger than inner_radius"};
    return std::nullopt;
}

}  // namespace rsl
