#include "tools/bench/bench.h"

#include <cstdio>

namespace rsl::bench {

std::vector<Benchmark>& benchmark_registry() {
    static std::vector<Benchmark> registry;
    return registry;
}

std::vector<nlohmann::json>& bench_results() {
    static std::vector<nlohmann::json> results;
    return results;
}

void bench_emit(nlohmann::json result) {
    std::fputs((result.dump() + "\n").c_str(), stdout);
    std::fflush(stdout);
    bench_results().push_back(std::move(result));
}

}  // namespace rsl::bench
