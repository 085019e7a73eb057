// Bottom-up decomposition: energy, region count and connectivity, agreement
// with the paper's brute-force O(m²)-per-step loop, and what it makes of
// simple maps.
#include <map>
#include <random>
#include <set>

#include <catch2/catch.hpp>

#include "src/lightfit/decompose.h"
#include "tests/random_cases.h"

using namespace rsl;
using namespace rsl::lightfit;

namespace {

constexpr int kFacePlusZ = 4;

CubeMap random_map(int n, unsigned seed) {
    CubeMap map(n);
    std::mt19937 rng(seed);
    std::lognormal_distribution<float> lognormal(0.0f, 1.5f);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = test::random_vec3(lognormal, rng);
    return map;
}

// Each label's texels form one connected set under `map.neighbors`
// (restricted to one face when `same_face`).
void check_regions_connected(const CubeMap& map, const RslSet& set, bool same_face) {
    const int per_face = map.resolution() * map.resolution();
    const int count = int(set.lights.size());
    std::vector<int> seen_regions(count, 0);
    std::vector<bool> visited(map.texel_count(), false);
    for (int start = 0; start < map.texel_count(); ++start) {
        if (visited[start]) continue;
        const int label = set.region_of_texel[start];
        ++seen_regions[label];  // a second component of the same label fails below
        std::vector<int> stack = {start};
        visited[start] = true;
        int size = 0;
        while (!stack.empty()) {
            const int k = stack.back();
            stack.pop_back();
            ++size;
            for (int n : map.neighbors(k)) {
                if (visited[n] || set.region_of_texel[n] != label) continue;
                if (same_face) {
                    // Same-face regions never contain texels of two faces.
                    REQUIRE(n / per_face == start / per_face);
                }
                visited[n] = true;
                stack.push_back(n);
            }
        }
        CHECK(size == set.lights[label].texel_count);
    }
    for (int label = 0; label < count; ++label) CHECK(seen_regions[label] == 1);
}

std::set<std::set<int>> partition_of(const RslSet& set) {
    std::map<int, std::set<int>> by_label;
    for (int k = 0; k < int(set.region_of_texel.size()); ++k) by_label[set.region_of_texel[k]].insert(k);
    std::set<std::set<int>> out;
    for (auto& [label, texels] : by_label) out.insert(texels);
    return out;
}

// The paper's Figure 5 loop: at every step fit every adjacent pair and merge
// the cheapest. O(m²) fits per step; only for tiny maps.
std::set<std::set<int>> brute_force_partition(const CubeMap& map, const DecomposeOptions& options) {
    const auto texels = make_fit_texels(map);
    const int per_face = map.resolution() * map.resolution();
    std::vector<std::vector<int>> regions;
    std::vector<RegionStats> stats;
    std::vector<double> errors;
    std::vector<int> label(map.texel_count());
    SquareFitter fitter;
    for (int k = 0; k < map.texel_count(); ++k) {
        regions.push_back({k});
        stats.push_back(RegionStats::of_texel(texels[k]));
        errors.push_back(fitter.fit(texels, stats.back(), regions.back(), {}, options.merge_fit).error);
        label[k] = k;
    }
    std::vector<bool> alive(regions.size(), true);
    for (int count = map.texel_count(); count > options.lights; --count) {
        double best_cost = std::numeric_limits<double>::max();
        int best_a = -1, best_b = -1;
        std::set<std::pair<int, int>> tried;
        for (int k = 0; k < map.texel_count(); ++k)
            for (int n : map.neighbors(k)) {
                if (!options.cross_face && n / per_face != k / per_face) continue;
                int a = label[k], b = label[n];
                if (a == b) continue;
                if (regions[a].size() < regions[b].size()) std::swap(a, b);  // as the merger orders them
                if (!tried.insert({std::min(a, b), std::max(a, b)}).second) continue;
                const double error = fitter.fit(texels, stats[a] + stats[b], regions[a], regions[b], options.merge_fit).error;
                const double cost = options.cost == MergeCost::kMergedError ? error : error - errors[a] - errors[b];
                if (cost < best_cost) best_cost = cost, best_a = a, best_b = b;
            }
        REQUIRE(best_a >= 0);
        regions[best_a].insert(regions[best_a].end(), regions[best_b].begin(), regions[best_b].end());
        stats[best_a] += stats[best_b];
        errors[best_a] = fitter.fit(texels, stats[best_a], regions[best_a], {}, options.merge_fit).error;
        for (int k : regions[best_b]) label[k] = best_a;
        regions[best_b].clear();
    }
    std::set<std::set<int>> out;
    for (auto& r : regions)
        if (!r.empty()) out.insert(std::set<int>(r.begin(), r.end()));
    return out;
}

}  // namespace

TEST_CASE("the RSL set keeps the map's energy per channel", "[lightfit][decompose]") {
    const CubeMap map = random_map(12, 1);
    const DVec3 energy = map.energy();
    for (bool cross : {true, false})
        for (MergeCost cost : {MergeCost::kMergedError, MergeCost::kErrorIncrease}) {
            const RslSet set = decompose(map, {.lights = 20, .cross_face = cross, .cost = cost});
            const DVec3 lights = set.total_energy();
            INFO("cross_face " << cross << ", cost " << int(cost));
            for (int ch = 0; ch < 3; ++ch) CHECK(std::abs(lights[ch] - energy[ch]) <= 1e-5 * energy[ch]);
        }
}

TEST_CASE("both merge rules end with exactly K connected regions", "[lightfit][decompose]") {
    const CubeMap map = random_map(10, 2);
    for (bool cross : {true, false})
        for (int k : {6, 13, 40}) {
            INFO("cross_face " << cross << ", K " << k);
            const RslSet set = decompose(map, {.lights = k, .cross_face = cross});
            REQUIRE(int(set.lights.size()) == k);
            REQUIRE(set.region_of_texel.size() == size_t(map.texel_count()));
            check_regions_connected(map, set, !cross);
        }
    // Cross-face merging can go below one region per face; same-face cannot.
    CHECK(decompose(map, {.lights = 2, .cross_face = true}).lights.size() == 2);
    CHECK(decompose(map, {.lights = 2, .cross_face = false}).lights.size() == 6);
}

TEST_CASE("the priority-queue merge makes the same regions as the paper's brute-force loop",
          "[lightfit][decompose]") {
    const CubeMap map = random_map(4, 3);
    for (bool cross : {true, false})
        for (MergeCost cost : {MergeCost::kMergedError, MergeCost::kErrorIncrease}) {
            INFO("cross_face " << cross << ", cost " << int(cost));
            const DecomposeOptions options{.lights = 9, .cross_face = cross, .cost = cost};
            CHECK(partition_of(decompose(map, options)) == brute_force_partition(map, options));
        }
}

TEST_CASE("one bright texel in a dark map becomes one small RSL centred on it", "[lightfit][decompose]") {
    CubeMap map(16);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(0.02f, 0.03f, 0.04f);
    const int bright = map.index(kFacePlusZ, 6, 9);
    map.radiance(bright) = Color(500.0f, 400.0f, 300.0f);
    const float texel_angle = std::sqrt(map.solid_angle(bright));
    for (bool cross : {true, false}) {
        const RslSet set = decompose(map, {.lights = 12, .cross_face = cross});
        const auto& light = set.lights[set.region_of_texel[bright]];
        INFO("cross_face " << cross << ", texels in its region " << light.texel_count);
        CHECK(std::acos(std::min(1.0f, glm::dot(light.center, map.texel_direction(bright)))) < 0.25f * texel_angle);
        CHECK(light.solid_angle() < 2.0f * map.solid_angle(bright));
        // It carries (nearly) all of the bright texel's energy.
        CHECK(light.light_integral().x > 0.99 * 500.0 * map.solid_angle(bright));
    }
}

TEST_CASE("a bright square patch is recovered as one RSL", "[lightfit][decompose]") {
    CubeMap map(32);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(0.05f);
    std::vector<int> patch;
    for (int j = 5; j < 13; ++j)
        for (int i = 14; i < 22; ++i) patch.push_back(map.index(kFacePlusZ, i, j));
    DVec3 sum(0.0);
    double patch_area = 0;
    for (int k : patch) {
        map.radiance(k) = Color(20.0f, 15.0f, 10.0f);
        sum += DVec3(map.texel_direction(k)) * double(map.solid_angle(k));
        patch_area += map.solid_angle(k);
    }
    const Vec3 patch_center(glm::normalize(sum));
    const float patch_r = float(std::sqrt(patch_area / 2));
    const float texel_angle = std::sqrt(map.solid_angle(patch[0]));
    // Lights go where the energy is: with more lights than the patch needs
    // the bright patch is split first. With one light for the background
    // (cross-face) or one per face (same-face) the patch is a region of its own.
    for (bool cross : {true, false})
        for (MergeCost cost : {MergeCost::kMergedError, MergeCost::kErrorIncrease}) {
            const RslSet set = decompose(map, {.lights = cross ? 2 : 7, .cross_face = cross, .cost = cost});
            const auto& light = set.lights[set.region_of_texel[patch[27]]];
            INFO("cross_face " << cross << ", cost " << int(cost));
            CHECK(light.texel_count == int(patch.size()));
            CHECK(std::acos(std::min(1.0f, glm::dot(light.center, patch_center))) < texel_angle);
            CHECK(light.half_diagonal == Approx(patch_r).epsilon(0.10));
        }
}

TEST_CASE("a uniform map splits into regions of similar size", "[lightfit][decompose]") {
    CubeMap map(16);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(1.0f);
    // Greedy pairwise merging grows regions in doublings and prefers square
    // shapes, so sizes come in steps; measured on this map (K 24..96): largest
    // / smallest ≤ 4.0 with the paper's rule, ≤ 5.2 with the increase rule on
    // an AVX-512 build and 6.4 on an AVX2 one (on a uniform map every merge
    // ties, and rounding picks among them); coefficient of variation ≤ 0.37
    // and ≤ 0.47. A merge that lets one region run away (or never merges some
    // texels) breaks both bounds by far.
    for (int k : {24, 96})
        for (MergeCost cost : {MergeCost::kMergedError, MergeCost::kErrorIncrease})
            for (bool cross : {true, false}) {
                const RslSet set = decompose(map, {.lights = k, .cross_face = cross, .cost = cost});
                std::vector<double> area(set.lights.size(), 0.0);
                for (int t = 0; t < map.texel_count(); ++t) area[set.region_of_texel[t]] += map.solid_angle(t);
                const auto [smallest, largest] = std::minmax_element(area.begin(), area.end());
                double mean = 0, variance = 0;
                for (double a : area) mean += a / area.size();
                for (double a : area) variance += (a - mean) * (a - mean) / area.size();
                INFO("K " << k << ", cost " << int(cost) << ", cross_face " << cross << ": solid angles "
                          << *smallest << " .. " << *largest);
                CHECK(*largest / *smallest < 8.0);
                CHECK(std::sqrt(variance) / mean < 0.5);
            }
}

TEST_CASE("an error threshold drives the number of lights", "[lightfit][decompose]") {
    const CubeMap map = random_map(12, 5);
    size_t previous = map.texel_count() + 1;
    for (double threshold : {1e-6, 1e-5, 1e-4, 1e-3}) {
        const RslSet set = decompose(map, {.lights = 1, .max_error = threshold});
        INFO("threshold " << threshold << ": " << set.lights.size() << " lights");
        CHECK(set.lights.size() < previous);
        CHECK(set.lights.size() > 1);
        for (const auto& light : set.lights) CHECK(light.fit_error <= threshold);
        previous = set.lights.size();
    }
}
