#pragma once
// `rsl bench`: every benchmark registers itself from a tools/bench/bench_<area>.cpp
// and prints one JSON object per line (machine-readable), e.g.
//   {"bench":"lightfit","case":"grace 6x32x32 -> 30","seconds":0.21,...}
// Times are wall-clock on the machine that runs it; prefer ratios measured in
// the same run (ours vs ground truth) when claiming speed-ups.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rsl::bench {

// Where the benchmarks find their inputs. The library knows no source tree:
// `rsl bench` passes these (defaults under the checkout it was built from).
struct BenchOptions {
    bool quick = false;                    // smaller cases, for smoke tests
    std::filesystem::path shared_assets;   // ../shared/assets (real probes/meshes), may be absent
    std::filesystem::path generated_assets;  // assets/generated
    std::filesystem::path scenes;          // assets/scenes
    std::filesystem::path output = "bench-out";  // plots and generated scenes (`--out`)
    std::vector<int> scale_parts;          // `bench scale` instance counts (empty: its defaults)
    std::vector<float> scale_reaches;      // `bench scale` OVDF outer radii (empty: the scene's)
    // Field cache of the scenes read from `scenes` (`--cache`; empty: beside
    // each scene file), so that a bench of an installed or read-only tree
    // writes nothing there.
    std::filesystem::path field_cache;
};

// Emit one result line (also collected for --json-out).
void bench_emit(nlohmann::json result);
// Every line emitted so far, in order.
std::vector<nlohmann::json>& bench_results();

// Timing helpers shared by the bench_<area>.cpp files.
using BenchClock = std::chrono::steady_clock;
inline double seconds_since(BenchClock::time_point start) {
    return std::chrono::duration<double>(BenchClock::now() - start).count();
}
// CPU time of the whole process (all threads). On a shared machine a
// difference of it divided by the cores used is the time on dedicated cores.
inline double process_cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }
// Best (minimum) wall time of `repeats` runs: the least noisy estimate on a
// shared machine for I/O- and allocation-bound work.
template <typename F>
double best_seconds(int repeats, F&& run) {
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
        const auto start = BenchClock::now();
        run();
        best = std::min(best, seconds_since(start));
    }
    return best;
}

struct Benchmark {
    std::string name;         // selects with `rsl bench NAME`
    std::string description;
    std::function<void(const BenchOptions&)> run;  // calls bench_emit per result
};

std::vector<Benchmark>& benchmark_registry();

struct RegisterBenchmark {
    explicit RegisterBenchmark(Benchmark b) { benchmark_registry().push_back(std::move(b)); }
};

}  // namespace rsl::bench
