#pragma once
// What the comparison experiments (`rsl baselines`, `rsl baselines
// --many-light`) share: the scene as compared and the frame timer.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/scene.h"

namespace rsl {

// The scene as compared: `environment` (a probe's path; empty: the scene's)
// swapped in without its blend, the cube map resolution set (> 0), and with
// `diffuse` every material made Lambertian of its own diffuse colour.
void adapt_scene(Scene& scene, const std::string& environment, int resolution, bool diffuse);

// Throws rsl::Error when a file the experiment writes into `folder` (an .exr
// and a .png per image stem, and the named files) is one of the scene's
// inputs, before anything is written: an input kept in the output folder
// under such a name is refused, not replaced (check_outputs_apart).
void check_experiment_outputs(const Scene& scene, const std::filesystem::path& folder,
                              const std::vector<std::string>& image_stems, const std::vector<std::string>& files);

using ExperimentClock = std::chrono::steady_clock;
inline double seconds_since(ExperimentClock::time_point start) {
    return std::chrono::duration<double>(ExperimentClock::now() - start).count();
}

// Median wall time of `repeats` calls (at least one), in milliseconds.
template <typename Frame>
double median_ms(int repeats, const Frame& frame) {
    std::vector<double> ms;
    for (int r = 0; r < std::max(1, repeats); ++r) {
        const auto start = ExperimentClock::now();
        frame();
        ms.push_back(1e3 * seconds_since(start));
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

}  // namespace rsl
