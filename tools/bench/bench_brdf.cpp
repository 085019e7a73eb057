// `rsl bench brdf`: BRDF table build times per model (iso and aniso), square
// lookups per second (single and batched), the float storage's precision, and
// the square approximation's own error (the RSL's true spherical region vs the
// plane square that replaces it). docs/design/BRDF.md quotes these numbers.
#include <algorithm>
#include <chrono>
#include <random>
#include <thread>

#include "src/brdf/brdf_table.h"
#include "src/shading/brdf_sat.h"
#include "tools/bench/bench.h"
#include "src/core/hemisphere.h"

namespace rsl::bench {
namespace {

MaterialDesc material(const std::string& model, std::map<std::string, std::vector<float>> params) {
    MaterialDesc m;
    m.name = model;
    m.model = model;
    m.params = std::move(params);
    return m;
}

std::vector<MaterialDesc> bench_materials() {
    return {
        material("lambert", {{"albedo", {0.8f}}}),
        material("phong", {{"kd", {0.2f}}, {"ks", {0.7f}}, {"exponent", {40}}}),
        material("blinn_phong", {{"kd", {0.2f}}, {"ks", {0.7f}}, {"exponent", {80}}}),
        material("cook_torrance_beckmann", {{"kd", {0.3f}}, {"f0", {0.9f, 0.6f, 0.3f}}, {"roughness", {0.2f}}}),
        material("cook_torrance_ggx", {{"kd", {0.3f}}, {"f0", {0.9f, 0.6f, 0.3f}}, {"roughness", {0.2f}}}),
        material("ward", {{"kd", {0.3f}}, {"ks", {0.6f}}, {"alpha", {0.15f}}}),
        material("ward_anisotropic", {{"kd", {0.2f}}, {"ks", {0.7f}}, {"alpha_x", {0.08f}}, {"alpha_y", {0.3f}}}),
    };
}

Vec3 random_upper(std::mt19937& rng, float max_theta) {
    std::uniform_real_distribution<float> u(0, 1);
    const float cos_theta = 1.0f - u(rng) * (1.0f - std::cos(max_theta));
    const float phi = 2.0f * kPi * u(rng);
    const float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    return Vec3(s * std::cos(phi), s * std::sin(phi), cos_theta);
}

// Table build times. Anisotropic tables are the 4D ones; isotropic models are
// also built as 4D tables to show what the 3D layout saves.
void bench_build(const BenchOptions& options) {
    for (const MaterialDesc& m : bench_materials()) {
        auto brdf = make_brdf(m);
        const int runs = options.quick ? 1 : (brdf->isotropic() ? 9 : 3);
        std::vector<double> times, cpu;
        std::shared_ptr<const BrdfTable> table;
        for (int k = 0; k < runs; ++k) {
            const auto start = BenchClock::now();
            const double cpu_start = process_cpu_seconds();
            table = BrdfTable::build(*brdf);
            times.push_back(seconds_since(start));
            cpu.push_back(process_cpu_seconds() - cpu_start);
        }
        std::sort(times.begin(), times.end());
        std::sort(cpu.begin(), cpu.end());
        const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
        bench_emit({{"bench", "brdf"},
                    {"case", "table build " + m.model},
                    {"layout", table->isotropic() ? "3D iso 32 views x 32x32" : "4D aniso 32x32 views x 32x32"},
                    {"seconds_median", times[times.size() / 2]},
                    {"seconds_min", times.front()},
                    {"cpu_seconds_median", cpu[cpu.size() / 2]},
                    {"cpu_seconds_per_thread_median", cpu[cpu.size() / 2] / threads},
                    {"runs", runs},
                    {"goal_seconds", table->isotropic() ? 0.005 : 0.150},
                    {"threads", threads},
                    {"bytes", table->memory_bytes()}});
    }
}

// Lookups per second: random squares (h from 0.01 to 0.25) and views. The
// batched path is timed as the CPU renderer calls it: blocks of at most 256
// queries (one light, one block of vertices), each block one call; best of 3.
// "coherent views": each block's views lie within ~0.15 rad of one direction,
// as for neighbouring vertices (for 4D tables, whose random views miss the cache).
void bench_lookups(const BenchOptions& options) {
    const size_t n = options.quick ? 100000 : 2000000;
    const size_t block = 256;
    const std::pair<const char*, bool> cases[] = {{"lambert", false},
                                                  {"blinn_phong", false},
                                                  {"cook_torrance_ggx", false},
                                                  {"ward_anisotropic", false},
                                                  {"ward_anisotropic", true}};
    for (auto [model, coherent] : cases) {
        MaterialDesc m;
        for (auto& d : bench_materials())
            if (d.model == model) m = d;
        auto table = BrdfTable::build(*make_brdf(m));
        std::vector<float> cx(n), cy(n), h(n), vx(n), vy(n), vz(n), r(n), g(n), b(n);
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> u(0, 1);
        Vec3 block_view(0, 0, 1);
        for (size_t k = 0; k < n; ++k) {
            const Vec2 p = hemisphere_to_plane(random_upper(rng, 1.55f));
            cx[k] = p.x, cy[k] = p.y, h[k] = 0.01f + 0.24f * u(rng);
            Vec3 v = random_upper(rng, 1.5f);
            if (coherent) {
                if (k % block == 0) block_view = random_upper(rng, 1.35f);
                v = glm::normalize(block_view + 0.15f * random_upper(rng, kPi));
            }
            vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
        }
        auto start = BenchClock::now();
        double cpu_start = process_cpu_seconds();
        float checksum = 0;
        for (size_t k = 0; k < n; ++k) checksum += table->square_average(Vec2(cx[k], cy[k]), h[k], Vec3(vx[k], vy[k], vz[k])).g;
        const double single = seconds_since(start), single_cpu = process_cpu_seconds() - cpu_start;
        double batched = 1e30, batched_cpu = 1e30;
        for (int run = 0; run < 3; ++run) {
            start = BenchClock::now();
            cpu_start = process_cpu_seconds();
            for (size_t k0 = 0; k0 < n; k0 += block) {
                const size_t count = std::min(block, n - k0);
                table->square_average_batch({cx.data() + k0, cy.data() + k0, h.data() + k0, 0.0f, vx.data() + k0,
                                             vy.data() + k0, vz.data() + k0, count},
                                            {r.data() + k0, g.data() + k0, b.data() + k0});
            }
            batched = std::min(batched, seconds_since(start));
            batched_cpu = std::min(batched_cpu, process_cpu_seconds() - cpu_start);
        }
        for (size_t k = 0; k < n; k += 997) checksum += g[k];
        bench_emit({{"bench", "brdf"},
                    {"case", std::string("lookups ") + (table->isotropic() ? "iso " : "aniso ") + model +
                                 (coherent ? " coherent views" : "")},
                    {"view_independent", table->view_independent()},
                    {"queries", n},
                    {"batch_size", block},
                    {"single_per_second", n / single},
                    {"batched_per_second", n / batched},
                    {"single_per_cpu_second", n / single_cpu},
                    {"batched_per_cpu_second", n / batched_cpu},
                    {"batched_ns_per_lookup", 1e9 * batched / n},
                    {"threads", 1},
                    {"checksum", checksum}});
    }
}

// Float storage precision: square averages from the stored table vs the
// exact (double) integral of the same texels, for both storages. A square
// is read at least one texel wide (shading::kMinSquareTexels), so is this one.
DVec3 exact_square_integral(const BrdfTable& t, int s, Vec2 c, float h) {
    const int n = t.grid().n;
    const double scale = 0.5 * n;
    h = std::max(h, shading::kMinSquareTexels / float(n));
    const double x0 = std::clamp((c.x - h + 1.0) * scale, 0.0, double(n)), x1 = std::clamp((c.x + h + 1.0) * scale, 0.0, double(n));
    const double y0 = std::clamp((c.y - h + 1.0) * scale, 0.0, double(n)), y1 = std::clamp((c.y + h + 1.0) * scale, 0.0, double(n));
    DVec3 sum(0.0);
    for (int j = int(y0); j < std::min(int(std::ceil(y1)), n); ++j)
        for (int i = int(x0); i < std::min(int(std::ceil(x1)), n); ++i) {
            const double w = std::max(0.0, std::min(x1, i + 1.0) - std::max(x0, double(i))) *
                             std::max(0.0, std::min(y1, j + 1.0) - std::max(y0, double(j)));
            sum += w * DVec3(t.texel(s, i, j));
        }
    return sum / ((2.0 * h * scale) * (2.0 * h * scale));
}

void bench_storage(const BenchOptions& options) {
    const int cases = options.quick ? 2000 : 50000;
    for (const MaterialDesc& m : {bench_materials()[0], bench_materials()[4],
                                  material("phong", {{"ks", {1.0f}}, {"exponent", {500}}})}) {
        auto brdf = make_brdf(m);
        for (SatStorage storage : {SatStorage::Float, SatStorage::FloatMeanOffset}) {
            BrdfTableOptions o;
            o.storage = storage;
            auto table = BrdfTable::build(*brdf, o);
            std::mt19937 rng(5);
            std::uniform_real_distribution<float> u(0, 1);
            double worst = 0, sum = 0, worst_small = 0;
            for (int k = 0; k < cases; ++k) {
                const int s = int(u(rng) * table->slice_count()) % table->slice_count();
                const Vec2 c = hemisphere_to_plane(random_upper(rng, 1.5f));
                const float h = 0.01f + 0.24f * u(rng);
                const double exact = luminance(Color(exact_square_integral(*table, s, c, h)));
                if (exact < 1e-4) continue;
                const double err = std::abs(luminance(table->slice_square_average(s, c, h)) - exact) / exact;
                worst = std::max(worst, err);
                if (h < 0.03f) worst_small = std::max(worst_small, err);
                sum += err;
            }
            bench_emit({{"bench", "brdf"},
                        {"case", std::string("float storage ") + (storage == SatStorage::Float ? "plain" : "mean offset") +
                                     " " + m.model + (m.params.count("exponent") ? " n=" + std::to_string(int(m.params.at("exponent")[0])) : "")},
                        {"squares", cases},
                        {"relative_error_mean", sum / cases},
                        {"relative_error_max", worst},
                        {"relative_error_max_h_below_0.03", worst_small}});
        }
    }
}

// The square approximation's own error (exact model, no table): the RSL
// ⟨c, r⟩ covers a spherical square: the square of half-edge a on the tangent
// plane at c, turned by a random angle about c, projected onto the sphere
// (gnomonic), with a chosen so that its solid angle is exactly 2r²
// (Ω = 4·asin(a²/(1 + a²)), so a² = s/(1 − s), s = sin(r²/2)). The renderer
// replaces it by the axis-aligned plane square of half-edge r/2 at p(c)
// (same measure). Both averages of ρ·cos (0 below the horizon) by G×G midpoint.
double region_average(const Brdf& brdf, const Vec3& c, float r, float turn, const Vec3& wo, int grid) {
    const double s = std::sin(0.5 * r * r);
    const double a = std::sqrt(s / (1.0 - s));
    const Frame f = Frame::from_normal(c);
    const Vec3 t1 = std::cos(turn) * f.x + std::sin(turn) * f.y, t2 = glm::cross(c, t1);
    double sum = 0, weight = 0;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const double x = a * (-1.0 + (2.0 * i + 1.0) / grid), y = a * (-1.0 + (2.0 * j + 1.0) / grid);
            const double jacobian = 1.0 / std::pow(1.0 + x * x + y * y, 1.5);  // dω / (dx dy)
            const Vec3 w = glm::normalize(c + float(x) * t1 + float(y) * t2);
            weight += jacobian;
            if (w.z > 0) sum += jacobian * double(luminance(brdf.eval(w, wo))) * w.z;
        }
    return sum / weight;
}

double plane_square_average(const Brdf& brdf, const Vec2& p, float h, const Vec3& wo, int grid) {
    double sum = 0;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const Vec2 q = p + h * Vec2(-1.0f + (2.0f * i + 1.0f) / grid, -1.0f + (2.0f * j + 1.0f) / grid);
            if (glm::dot(q, q) >= 1.0f) continue;
            const Vec3 w = plane_to_hemisphere(q);
            sum += double(luminance(brdf.eval(w, wo))) * w.z;
        }
    return sum / (grid * grid);
}

void bench_square_approximation(const BenchOptions& options) {
    const int trials = options.quick ? 100 : 1000;
    const int grid = options.quick ? 24 : 40;
    for (const MaterialDesc& m : {bench_materials()[0], bench_materials()[1], bench_materials()[4],
                                  bench_materials()[6]}) {
        auto brdf = make_brdf(m);
        for (float r : {0.02f, 0.05f, 0.1f, 0.2f, 0.3f, 0.5f}) {
            std::mt19937 rng(7);
            std::uniform_real_distribution<float> u(0, 1);
            std::vector<double> errors;
            double abs_sum = 0, ref_sum = 0;
            for (int k = 0; k < trials; ++k) {
                const Vec3 wo = random_upper(rng, 1.4f);
                const Vec3 c = random_upper(rng, 0.5f * kPi);
                const double truth = region_average(*brdf, c, r, u(rng) * 0.5f * kPi, wo, grid);
                const double square = plane_square_average(*brdf, hemisphere_to_plane(c), square_half_edge_for_rsl(r), wo, grid);
                if (truth <= 1e-6) continue;
                errors.push_back(std::abs(square - truth) / truth);
                abs_sum += std::abs(square - truth);
                ref_sum += truth;
            }
            std::sort(errors.begin(), errors.end());
            auto q = [&](double f) { return errors[size_t(f * (errors.size() - 1))]; };
            bench_emit({{"bench", "brdf"},
                        {"case", "square approximation " + m.model},
                        {"r", r},
                        {"trials", errors.size()},
                        {"relative_error_median", q(0.5)},
                        {"relative_error_p90", q(0.9)},
                        {"relative_error_p99", q(0.99)},
                        {"relative_error_energy", abs_sum / ref_sum}});
        }
    }
}

RegisterBenchmark brdf_benchmark({"brdf",
    "BRDF tables: build time per model, lookups/s (single, batched), float storage precision, square approximation error",
    [](const BenchOptions& options) {
        bench_build(options);
        bench_lookups(options);
        bench_storage(options);
        bench_square_approximation(options);
    }});

}  // namespace
}  // namespace rsl::bench
