// `rsl bench env`: environment-map resampling. For each real probe and cube
// resolution: the time to resample lat-long → 6×N×N (cold: fitting the
// overlap weights; warm: reusing them), and the energy error against the
// source's exact integral. Also the flatness of a resampled constant map (the
// weights' row error) and rotation time and energy error.
#include <algorithm>
#include <chrono>
#include <vector>

#include <fmt/core.h>
#include <glm/gtc/quaternion.hpp>

#include "tools/bench/bench.h"
#include "src/core/envmap.h"
#include "src/formats/image_file.h"

namespace rsl::bench {
namespace {

double worst_channel_error(const DVec3& got, const DVec3& want) {
    double worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - want[c]) / want[c]);
    return worst;
}

// Cold time (weights fitted from scratch) and median warm time of f().
template <typename F>
std::pair<double, double> time_cold_warm(int warm_runs, F f) {
    clear_resampling_cache();
    auto start = BenchClock::now();
    f();
    const double cold = seconds_since(start);
    std::vector<double> warm;
    for (int k = 0; k < warm_runs; ++k) {
        start = BenchClock::now();
        f();
        warm.push_back(seconds_since(start));
    }
    std::sort(warm.begin(), warm.end());
    return {cold, warm[warm.size() / 2]};
}

void bench_probes(const BenchOptions& options, const std::vector<int>& resolutions) {
    const std::filesystem::path probes = options.shared_assets / "probes";
    std::vector<std::string> names = {"grace", "uffizi", "ennis"};
    if (options.quick) names.resize(1);
    for (const std::string& name : names) {
        const std::filesystem::path path = probes / (name + ".hdr");
        if (!std::filesystem::exists(path)) {
            bench_emit({{"bench", "env"}, {"case", "probe " + name}, {"skipped", path.string() + " is absent"}});
            continue;
        }
        auto start = BenchClock::now();
        const Image image = read_hdr_image(path);
        const double read_seconds = seconds_since(start);
        const DVec3 source = latlong_energy(image);
        for (int n : resolutions) {
            CubeMap map;
            const auto [cold, warm] = time_cold_warm(options.quick ? 1 : 5, [&] { map = cube_from_latlong(image, n); });
            bench_emit({{"bench", "env"},
                        {"case", fmt::format("{} {}x{} -> 6x{}x{}", name, image.width, image.height, n, n)},
                        {"read_seconds", read_seconds},
                        {"resample_seconds_cold", cold},
                        {"resample_seconds_warm", warm},
                        {"energy_relative_error", worst_channel_error(map.energy(), source)},
                        {"source_energy_rgb", {source.r, source.g, source.b}}});
        }
    }
}

void bench_flatness(const std::vector<int>& resolutions) {
    Image flat(256, 128, 3);
    std::fill(flat.pixels.begin(), flat.pixels.end(), 1.0f);
    for (int n : resolutions) {
        const CubeMap map = cube_from_latlong(flat, n);
        double worst = 0;
        for (const Color& c : map.radiances()) worst = std::max(worst, double(std::abs(c.g - 1.0f)));
        bench_emit({{"bench", "env"},
                    {"case", fmt::format("constant 256x128 -> 6x{}x{}", n, n)},
                    {"worst_texel_relative_error", worst}});
    }
}

void bench_rotation(const BenchOptions& options, const std::vector<int>& resolutions) {
    for (int n : resolutions) {
        CubeMap map(n);
        for (int k = 0; k < map.texel_count(); ++k) {
            const Vec3 d = map.texel_direction(k);
            map.radiance(k) = Color(1.0f + d.x, 1.0f + d.y * d.y, 0.2f) * (k % 97 == 0 ? 100.0f : 1.0f);
        }
        const Mat3 r = glm::mat3_cast(glm::angleAxis(0.7f, glm::normalize(Vec3(1, 2, 3))));
        CubeMap rotated;
        const auto [cold, warm] = time_cold_warm(options.quick ? 1 : 5, [&] { rotated = rotate(map, r); });
        bench_emit({{"bench", "env"},
                    {"case", fmt::format("rotate 6x{}x{}", n, n)},
                    {"seconds_cold", cold},
                    {"seconds_warm", warm},
                    {"energy_relative_error", worst_channel_error(rotated.energy(), map.energy())}});
    }
}

RegisterBenchmark bench_env({"env",
    "Environment maps: lat-long -> cube resampling time (cold/warm) and energy error per probe and N; "
    "flatness; rotation",
    [](const BenchOptions& options) {
        const std::vector<int> resolutions = options.quick ? std::vector<int>{32} : std::vector<int>{32, 64, 128};
        bench_probes(options, resolutions);
        bench_flatness(resolutions);
        bench_rotation(options, resolutions);
    }});

}  // namespace
}  // namespace rsl::bench
