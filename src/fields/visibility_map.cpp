#include "src/fields/visibility_map.h"

#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "src/core/hemisphere.h"

namespace rsl {

HemisphereSampling::HemisphereSampling(int resolution, int supersampling, bool coarse_to_fine, float max_radius)
    : n_(resolution), k_(supersampling) {
    const float r2 = max_radius * max_radius;
    RSL_CHECK_GE(resolution, 2);
    RSL_CHECK_GE(supersampling, 1);
    const PlaneGrid grid{n_};
    const float texel = grid.texel_size();
    traced_mask_.assign(grid.size(), 0);
    sub_begin_.assign(grid.size() + 1, 0);
    extension_source_.assign(grid.size(), -1);
    for (int j = 0; j < n_; ++j)
        for (int i = 0; i < n_; ++i) {
            const int t = grid.index(i, j);
            const Vec2 p = grid.texel_center(i, j);
            sub_begin_[t] = int(sub_dirs_.size());
            if (glm::dot(p, p) >= r2) continue;
            traced_mask_[t] = 1;
            traced_.push_back(t);
            center_dirs_.push_back(plane_to_hemisphere(p));
            const Vec2 corner(-1.0f + i * texel, -1.0f + j * texel);
            for (int b = 0; b < k_; ++b)
                for (int a = 0; a < k_; ++a) {
                    const Vec2 q = corner + Vec2((a + 0.5f) / k_, (b + 0.5f) / k_) * texel;
                    if (glm::dot(q, q) < r2) sub_dirs_.push_back(plane_to_hemisphere(q));
                }
        }
    sub_begin_[grid.size()] = int(sub_dirs_.size());
    for (int c = 0; c < int(traced_.size()); ++c) {
        const int t = traced_[c];
        const bool even = (t % n_) % 2 == 0 && (t / n_) % 2 == 0;
        (even || !coarse_to_fine ? coarse_ : fine_).push_back(c);
    }
    // Below-horizon texels copy the first traced texel met walking radially inwards.
    for (int j = 0; j < n_; ++j)
        for (int i = 0; i < n_; ++i) {
            const int t = grid.index(i, j);
            if (traced_mask_[t]) continue;
            const Vec2 p = grid.texel_center(i, j);
            const Vec2 dir = p / glm::length(p);
            for (float r = 1.0f; r > 0.0f; r -= 0.25f * texel) {
                const Vec2 tc = grid.to_texel_coords(dir * r);
                const int si = std::clamp(int(tc.x), 0, n_ - 1), sj = std::clamp(int(tc.y), 0, n_ - 1);
                if (traced_mask_[grid.index(si, sj)]) {
                    extension_source_[t] = grid.index(si, sj);
                    break;
                }
            }
        }
}

void trace_coverage(const RayScene& scene, const HemisphereSampling& sampling, const Vec3& origin,
                    const Frame& frame, BelowHorizon below_horizon, VisibilityScratch& scratch,
                    float* coverage) {
    const int n = sampling.resolution();
    const auto& traced = sampling.traced_texels();
    const auto& centers = sampling.center_directions();
    const int count = int(traced.size());
    constexpr float kFar = 1e30f;
    scratch.world_dirs.resize(std::max(count, int(sampling.subsample_directions().size())));
    scratch.hits.resize(scratch.world_dirs.size());
    scratch.boundary.clear();
    // Coarse to fine: first the texels with even (i, j), then the others only
    // where their traced even neighbours disagree (or are missing).
    auto trace_list = [&](const std::vector<int>& list_of_positions) {
        const int m = int(list_of_positions.size());
        for (int c = 0; c < m; ++c) scratch.world_dirs[c] = frame.to_world(centers[list_of_positions[c]]);
        scene.occluded_batch(origin, scratch.world_dirs.data(), m, 0.0f, kFar, scratch.hits.data());
        for (int c = 0; c < m; ++c) coverage[traced[list_of_positions[c]]] = scratch.hits[c] ? 1.0f : 0.0f;
    };
    const auto& coarse = sampling.coarse_positions();
    trace_list(coarse);
    scratch.fine.clear();
    for (int c : sampling.fine_positions()) {
        const int t = traced[c], i = t % n, j = t / n;
        const int i0 = i & ~1, j0 = j & ~1;
        const int i1 = (i & 1) ? i0 + 2 : i0, j1 = (j & 1) ? j0 + 2 : j0;
        float first = -1;
        bool agree = true;
        for (int jj : {j0, j1})
            for (int ii : {i0, i1}) {
                if (ii >= n || jj >= n || !sampling.is_traced(jj * n + ii)) { agree = false; continue; }
                const float v = coverage[jj * n + ii];
                if (first < 0) first = v;
                agree &= v == first;
            }
        if (agree) coverage[t] = first;
        else scratch.fine.push_back(c);
    }
    trace_list(scratch.fine);

    if (sampling.supersampling() > 1) {
        // Supersample the texels where the one-ray map changes.
        for (int c = 0; c < count; ++c) {
            const int t = traced[c], i = t % n, j = t / n;
            const float v = coverage[t];
            auto differs = [&](int s) { return sampling.is_traced(s) && coverage[s] != v; };
            if ((i > 0 && differs(t - 1)) || (i + 1 < n && differs(t + 1)) || (j > 0 && differs(t - n)) ||
                (j + 1 < n && differs(t + n)))
                scratch.boundary.push_back(t);
        }
        const auto& subs = sampling.subsample_directions();
        int total = 0;
        for (int t : scratch.boundary)
            for (int s = sampling.subsample_begin(t); s < sampling.subsample_end(t); ++s)
                scratch.world_dirs[total++] = frame.to_world(subs[s]);
        scene.occluded_batch(origin, scratch.world_dirs.data(), total, 0.0f, kFar, scratch.hits.data());
        int at = 0;
        for (int t : scratch.boundary) {
            const int m = sampling.subsample_end(t) - sampling.subsample_begin(t);
            if (m == 0) continue;  // keep the center ray's value
            int visible = 0;
            for (int s = 0; s < m; ++s) visible += scratch.hits[at + s];
            at += m;
            coverage[t] = float(visible) / float(m);
        }
    }

    for (int t = 0; t < n * n; ++t) {
        if (sampling.is_traced(t)) continue;
        switch (below_horizon) {
            case BelowHorizon::Blocked: coverage[t] = 0.0f; break;
            case BelowHorizon::Visible: coverage[t] = 1.0f; break;
            case BelowHorizon::Extend: {
                const int source = sampling.extension_source(t);
                RSL_CHECK_GE(source, 0);
                coverage[t] = coverage[source];
                break;
            }
        }
    }
}

std::vector<float> trace_vertex_vdts(const RayScene& scene, const TriangleMesh& mesh,
                                     const VisibilityMapOptions& options, const ProgressCallback& progress,
                                     const std::vector<uint32_t>* subset) {
    RSL_CHECK_EQ(mesh.normals.size(), mesh.positions.size());
    const int n = options.resolution;
    const size_t nn = size_t(n) * n;
    const size_t vertices = subset ? subset->size() : mesh.vertex_count();
    const HemisphereSampling sampling(n, options.supersampling, options.coarse_to_fine);
    const RayOffset offset{scene.world_diagonal()};
    // Where the truth starts a vertex's rays (PosedScene::vertex): one offset
    // into its own triangles on the border of its surface, one along its normal.
    const std::vector<Vec3> inward = border_inward_directions(mesh);
    std::vector<float> vdts(vertices * nn);
    std::atomic<size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 64), [&](const tbb::blocked_range<size_t>& range) {
        VisibilityScratch scratch;
        scratch.coverage.resize(nn);
        for (size_t k = range.begin(); k != range.end(); ++k) {
            const size_t v = subset ? (*subset)[k] : k;
            const Frame frame = vertex_frame(mesh, v);
            trace_coverage(scene, sampling, offset.origin(mesh.positions[v], frame.z, inward[v]), frame,
                           options.below_horizon, scratch, scratch.coverage.data());
            compute_vdt(n, scratch.coverage.data(), vdts.data() + k * nn, options.mode, scratch.vdt);
        }
        const size_t now = done.fetch_add(range.size()) + range.size();
        if (progress) progress(now, vertices);
    });
    return vdts;
}

}  // namespace rsl
