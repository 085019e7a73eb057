#pragma once
// `rsl bench`: every benchmark registers itself from a src/cli/bench_<area>.cpp
// and prints one JSON object per line (machine-readable), e.g.
//   {"bench":"lightfit","case":"grace 6x32x32 -> 30","seconds":0.21,...}
// Times are wall-clock on the machine that runs it; prefer ratios measured in
// the same run (ours vs ground truth) when claiming speed-ups.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rsl::cli {

struct BenchOptions {
    bool quick = false;                    // smaller cases, for smoke tests
    std::filesystem::path shared_assets;   // ../shared/assets (real probes/meshes), may be absent
    std::filesystem::path generated_assets;  // assets/generated
};

// Emit one result line (also collected for --json-out).
void bench_emit(nlohmann::json result);

struct Benchmark {
    std::string name;         // selects with `rsl bench NAME`
    std::string description;
    std::function<void(const BenchOptions&)> run;  // calls bench_emit per result
};

std::vector<Benchmark>& benchmark_registry();

struct RegisterBenchmark {
    explicit RegisterBenchmark(Benchmark b) { benchmark_registry().push_back(std::move(b)); }
};

}  // namespace rsl::cli
