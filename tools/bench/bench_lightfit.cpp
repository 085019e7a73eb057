// `rsl bench lightfit`: decomposition time (6×32×32 → 30 and 6×64×64 → 100
// RSLs; the paper: ~2 minutes for 6×32×32) and the relative L2 error of the
// reconstructed environment as K grows, for each merge rule (docs/design/LIGHTFIT.md).
#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/core.h>

#include "src/formats/environment_file.h"
#include "src/lightfit/decompose.h"
#include "src/lightfit/reconstruct.h"
#include "tools/bench/bench.h"
#include "src/core/envmap.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;

const char* cost_name(lightfit::MergeCost cost) {
    return cost == lightfit::MergeCost::kMergedError ? "merged" : "increase";
}

// The real probes, then the project's generated environments, whichever exist.
std::vector<fs::path> environments(const BenchOptions& options) {
    std::vector<fs::path> found;
    for (const char* name : {"grace.hdr", "uffizi.hdr", "ennis.hdr"})
        if (fs::exists(options.shared_assets / "probes" / name)) found.push_back(options.shared_assets / "probes" / name);
    for (const char* name : {"sunsky.exr", "studio.exr", "overcast.exr"})
        if (fs::exists(options.generated_assets / name)) found.push_back(options.generated_assets / name);
    return found;
}

struct Timing {
    double wall_seconds = 1e30;  // best of the repeats: the machine is shared, the minimum is the least disturbed
    double cpu_seconds = 1e30;   // process CPU time (all threads) of the same runs, best of the repeats
};

Timing time_decompose(const CubeMap& map, const lightfit::DecomposeOptions& options, int repeats) {
    Timing best;
    for (int r = 0; r < repeats; ++r) {
        const double cpu_start = process_cpu_seconds();
        const auto start = std::chrono::steady_clock::now();
        const RslSet set = lightfit::decompose(map, options);
        best.wall_seconds =
            std::min(best.wall_seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        best.cpu_seconds = std::min(best.cpu_seconds, process_cpu_seconds() - cpu_start);
    }
    return best;
}

void bench_lightfit(const BenchOptions& options) {
    const auto envs = environments(options);
    if (envs.empty()) {
        bench_emit({{"bench", "lightfit"}, {"skipped", "no probes in " + options.shared_assets.string() +
                                                           " and no generated environments"}});
        return;
    }
    struct TimingCase {
        int resolution, lights;
    };
    const std::vector<TimingCase> timing = options.quick ? std::vector<TimingCase>{{16, 10}}
                                                         : std::vector<TimingCase>{{32, 30}, {64, 100}};
    const std::vector<int> sweep = options.quick ? std::vector<int>{10} : std::vector<int>{10, 30, 60, 100};
    const int sweep_resolution = options.quick ? 16 : 32;

    for (size_t e = 0; e < (options.quick ? 1 : envs.size()); ++e) {
        const fs::path& path = envs[e];
        const std::string name = path.stem().string();
        for (const auto& t : timing) {
            const CubeMap map = load_environment(path, t.resolution);
            for (bool cross : {true, false}) {
                lightfit::DecomposeOptions o;
                o.lights = t.lights;
                o.cross_face = cross;
                const Timing timing = time_decompose(map, o, options.quick ? 1 : 3);
                bench_emit({{"bench", "lightfit"},
                            {"case", fmt::format("time {} 6x{}x{} -> {}", name, t.resolution, t.resolution, t.lights)},
                            {"environment", name},
                            {"resolution", t.resolution},
                            {"lights", t.lights},
                            {"cross_face", cross},
                            {"merge_cost", cost_name(o.cost)},
                            {"seconds", timing.wall_seconds},
                            {"cpu_seconds", timing.cpu_seconds},
                            {"goal_seconds", t.resolution <= 32 ? 0.5 : 5.0},
                            {"paper_seconds_6x32x32", 120}});
            }
        }
        const CubeMap map = load_environment(path, sweep_resolution);
        for (int k : sweep)
            for (bool cross : {true, false})
                for (auto cost : {lightfit::MergeCost::kMergedError, lightfit::MergeCost::kErrorIncrease}) {
                    lightfit::DecomposeOptions o;
                    o.lights = k;
                    o.cross_face = cross;
                    o.cost = cost;
                    const RslSet set = lightfit::decompose(map, o);
                    const double error = lightfit::relative_l2_error(map, lightfit::reconstruct(set, map.resolution()));
                    bench_emit({{"bench", "lightfit"},
                                {"case", fmt::format("error {} 6x{}x{} -> {} {} {}", name, sweep_resolution,
                                                     sweep_resolution, k, cross ? "cross-face" : "same-face",
                                                     cost_name(cost))},
                                {"environment", name},
                                {"resolution", sweep_resolution},
                                {"lights", k},
                                {"cross_face", cross},
                                {"merge_cost", cost_name(cost)},
                                {"relative_l2", error}});
                }
    }
}

RegisterBenchmark lightfit_benchmark({"lightfit",
    "RSL decomposition time (6x32x32->30, 6x64x64->100) and reconstruction error vs K, same-face vs cross-face",
    bench_lightfit});

}  // namespace
}  // namespace rsl::bench
