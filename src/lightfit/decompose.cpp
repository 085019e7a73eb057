#include "src/lightfit/decompose.h"

#include <algorithm>
#include <cstdint>
#include <queue>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "src/formats/image_file.h"

namespace rsl::lightfit {

namespace {

struct Region {
    RegionStats stats;
    std::vector<int> texels;
    std::vector<int> neighbors;  // sorted region ids
    double fit_error = 0;
    uint32_t version = 0;
    bool alive = true;
};

struct Candidate {
    double cost;
    double merged_error;
    int a, b;
    uint32_t version_a, version_b;
    // std::priority_queue is a max-heap; the cheapest candidate must come out
    // first, ties broken by region ids so runs are deterministic.
    bool operator<(const Candidate& o) const {
        if (cost != o.cost) return cost > o.cost;
        if (a != o.a) return a > o.a;
        return b > o.b;
    }
};

// Pairs with more texels than this are fitted in parallel after a merge.
constexpr int kParallelTexels = 2048;

class Merger {
public:
    Merger(const CubeMap& map, const DecomposeOptions& options)
        : options_(options), texels_(make_fit_texels(map)), regions_(texels_.size()) {
        const DVec3 total = map.energy();
        energy_norm2_ = std::max(glm::dot(total, total), 1e-300);
        const int n = map.resolution(), per_face = n * n;
        for (int k = 0; k < int(texels_.size()); ++k) {
            Region& region = regions_[k];
            region.stats = RegionStats::of_texel(texels_[k]);
            region.texels = {k};
            for (int other : map.neighbors(k))
                if (other >= 0 && other != k && (options.cross_face || other / per_face == k / per_face))
                    region.neighbors.push_back(other);
            std::sort(region.neighbors.begin(), region.neighbors.end());
            region.neighbors.erase(std::unique(region.neighbors.begin(), region.neighbors.end()),
                                   region.neighbors.end());
        }
        alive_count_ = int(regions_.size());
    }

    void run() {
        if (options_.cost == MergeCost::kErrorIncrease)
            tbb::parallel_for(0, int(regions_.size()), [&](int k) {
                Region& r = regions_[k];
                r.fit_error = fitter_.local().fit(texels_, r.stats, r.texels, {}, options_.merge_fit).error;
            });
        seed_queue();
        const int target = std::max(options_.lights, 1);
        while (alive_count_ > target && !queue_.empty()) {
            const Candidate c = queue_.top();
            queue_.pop();
            const Region &a = regions_[c.a], &b = regions_[c.b];
            if (!a.alive || !b.alive || a.version != c.version_a || b.version != c.version_b) continue;
            if (options_.max_error > 0 && c.merged_error / energy_norm2_ > options_.max_error) break;
            merge(c.a, c.b, c.merged_error);
        }
    }

    RslSet result() {
        std::vector<int> alive;
        for (int k = 0; k < int(regions_.size()); ++k)
            if (regions_[k].alive) alive.push_back(k);
        RslSet set;
        set.resolution = int(std::lround(std::sqrt(texels_.size() / 6.0)));
        set.lights.resize(alive.size());
        set.region_of_texel.assign(texels_.size(), -1);
        tbb::parallel_for(0, int(alive.size()), [&](int i) {
            const Region& region = regions_[alive[i]];
            const SquareFit fit = fitter_.local().fit(texels_, region.stats, region.texels, {}, options_.final_fit);
            set.lights[i] = {fit.center, fit.half_diagonal, fit.radiance, region.stats.texel_count,
                             float(fit.error / energy_norm2_)};
            for (int t : region.texels) set.region_of_texel[t] = i;
        });
        return set;
    }

private:
    Candidate make_candidate(int a, int b) {
        const Region &ra = regions_[a], &rb = regions_[b];
        const RegionStats merged = ra.stats + rb.stats;
        const double error = fitter_.local().fit(texels_, merged, ra.texels, rb.texels, options_.merge_fit).error;
        const double cost =
            options_.cost == MergeCost::kMergedError ? error : error - ra.fit_error - rb.fit_error;
        return {cost, error, a, b, ra.version, rb.version};
    }

    void seed_queue() {
        std::vector<std::pair<int, int>> pairs;
        for (int k = 0; k < int(regions_.size()); ++k)
            for (int n : regions_[k].neighbors)
                if (n > k) pairs.emplace_back(k, n);
        std::vector<Candidate> candidates(pairs.size());
        tbb::parallel_for(size_t(0), pairs.size(),
                          [&](size_t i) { candidates[i] = make_candidate(pairs[i].first, pairs[i].second); });
        queue_ = std::priority_queue<Candidate>(std::less<Candidate>(), std::move(candidates));
    }

    // Merges b into a (or a into b, whichever has fewer texels to move).
    void merge(int a, int b, double merged_error) {
        if (regions_[a].texels.size() < regions_[b].texels.size()) std::swap(a, b);
        Region &into = regions_[a], &from = regions_[b];
        into.stats += from.stats;
        into.texels.insert(into.texels.end(), from.texels.begin(), from.texels.end());
        into.fit_error = merged_error;
        ++into.version;
        from.alive = false;
        std::vector<int>().swap(from.texels);

        std::vector<int> neighbors;
        std::set_union(into.neighbors.begin(), into.neighbors.end(), from.neighbors.begin(), from.neighbors.end(),
                       std::back_inserter(neighbors));
        std::erase_if(neighbors, [&](int r) { return r == a || r == b; });
        into.neighbors = std::move(neighbors);
        for (int n : from.neighbors) {
            if (n == a) continue;
            auto& list = regions_[n].neighbors;
            std::erase(list, b);
            auto at = std::lower_bound(list.begin(), list.end(), a);
            if (at == list.end() || *at != a) list.insert(at, a);
        }
        std::vector<int>().swap(from.neighbors);
        --alive_count_;

        const auto& around = into.neighbors;
        pending_.resize(around.size());
        int texels_to_fit = 0;
        for (int n : around) texels_to_fit += into.stats.texel_count + regions_[n].stats.texel_count;
        if (texels_to_fit > kParallelTexels)
            tbb::parallel_for(size_t(0), around.size(), [&](size_t i) { pending_[i] = make_candidate(a, around[i]); });
        else
            for (size_t i = 0; i < around.size(); ++i) pending_[i] = make_candidate(a, around[i]);
        for (const auto& c : pending_) queue_.push(c);
    }

    const DecomposeOptions& options_;
    std::vector<FitTexel> texels_;
    std::vector<Region> regions_;
    std::priority_queue<Candidate> queue_;
    std::vector<Candidate> pending_;
    tbb::enumerable_thread_specific<SquareFitter> fitter_;
    double energy_norm2_ = 1;
    int alive_count_ = 0;
};

}  // namespace

RslSet decompose(const CubeMap& map, const DecomposeOptions& options) {
    RSL_CHECK_GT(map.texel_count(), 0);
    RSL_CHECK_GE(options.lights, 1);
    // Readers refuse such maps (check_radiance); maps built in code are
    // checked here, since the fit's float sums overflow on them (it then
    // compares NaN costs for minutes).
    for (int k = 0; k < map.texel_count(); ++k) {
        const Color& c = map.radiance(k);
        for (int channel = 0; channel < 3; ++channel)
            if (!(c[channel] >= 0.0f && c[channel] <= kMaxRadiance))
                throw_error("environment texel {} (direction {}, {}, {}) has radiance {} (channel {}): must be finite, "
                            "non-negative and at most 1e15",
                            k, map.texel_direction(k).x, map.texel_direction(k).y, map.texel_direction(k).z,
                            c[channel], "RGB"[channel]);
    }
    Merger merger(map, options);
    merger.run();
    return merger.result();
}

}  // namespace rsl::lightfit
