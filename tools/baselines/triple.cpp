// The triple-product baseline: per-vertex sparse visibility, per-material BRDF
// slice tables and the per-frame evaluation (triple.h).
#include "tools/baselines/triple.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "src/brdf/brdf.h"
#include "src/core/error.h"
#include "tools/baselines/thread_seconds.h"
#include "tools/baselines/triple_product.h"

namespace rsl {

namespace {

using baselines_timing::Clock;
using baselines_timing::seconds_since;

// One block of vertices' visibility rows, built by one thread.
struct VisibilityBlock {
    std::vector<uint64_t> row_size;
    std::vector<uint32_t> index;
    std::vector<float> value;
};

// Vertex phase: VΩ Haar-transformed per face into `g`; its coefficients above
// `drop` × the largest appended to the block.
void add_visibility_row(const float* V, const CubeMap& environment, float drop, std::vector<float>& g,
                        std::vector<float>& scratch, VisibilityBlock& block) {
    const int n = environment.resolution(), texels = environment.texel_count();
    for (int k = 0; k < texels; ++k) g[k] = V[k] * environment.solid_angle(k);
    for (int face = 0; face < 6; ++face) haar::forward_face(g.data() + size_t(face) * n * n, n, 1, scratch.data());
    float largest = 0.0f;
    for (int k = 0; k < texels; ++k) largest = std::max(largest, std::abs(g[k]));
    const float threshold = largest * drop;
    uint64_t kept = 0;
    for (int k = 0; k < texels; ++k) {
        if (g[k] == 0.0f || !(std::abs(g[k]) > threshold)) continue;
        block.index.push_back(uint32_t(k));
        block.value.push_back(g[k]);
        ++kept;
    }
    block.row_size.push_back(kept);
}

// Joins the blocks' rows in vertex order.
void join_blocks(const std::vector<VisibilityBlock>& blocks, SparseVisibility& out) {
    out.start.assign(1, 0);
    for (const VisibilityBlock& b : blocks) {
        for (uint64_t size : b.row_size) out.start.push_back(out.start.back() + size);
        out.index.insert(out.index.end(), b.index.begin(), b.index.end());
        out.value.insert(out.value.end(), b.value.begin(), b.value.end());
    }
}

// The view grid: an octahedral map of the upper hemisphere onto [−1, 1]²
// (turned 45°), R_v × R_v cells; a view below the horizon is clamped onto it.
// These are a local view's grid coordinates (row, column).
Vec2 view_coords(const Vec3& local) {
    const float z = std::max(local.z, 0.0f);
    const float sum = std::abs(local.x) + std::abs(local.y) + z;
    const float px = sum > 0 ? local.x / sum : 0.0f, py = sum > 0 ? local.y / sum : 0.0f;
    return Vec2(px - py, px + py);
}

int view_cell(const Vec3& local, int views) {
    const Vec2 coords = view_coords(local);
    const auto cell = [views](float u) { return std::clamp(int(std::floor((u + 1.0f) * 0.5f * views)), 0, views - 1); };
    return cell(coords.x) * views + cell(coords.y);
}

Vec3 view_direction(int cell, int views) {
    const float u = 2.0f * (float(cell % views) + 0.5f) / float(views) - 1.0f;
    const float v = 2.0f * (float(cell / views) + 0.5f) / float(views) - 1.0f;
    const float px = 0.5f * (u + v), py = 0.5f * (u - v);
    return glm::normalize(Vec3(px, py, 1.0f - std::abs(px) - std::abs(py)));
}

// Linear interpolation along one axis of `cells` cells over [−1, 1] between
// the centres of `first` and `first + 1`; clamped to the end cells (the view
// grid's ends are the horizon, the normals' are a face edge the caller crosses).
// Returns the weight of `first + 1`.
float axis_weight(float coord, int cells, bool clamp, int& first) {
    const float c = (coord + 1.0f) * 0.5f * float(cells) - 0.5f;
    if (!clamp) {
        first = int(std::floor(c));
        return c - float(first);
    }
    if (cells == 1) return first = 0, 0.0f;
    const float clamped = std::clamp(c, 0.0f, float(cells - 1));
    first = std::min(int(clamped), cells - 2);
    return clamped - float(first);
}

// The 2×2 tabulated normals around `normal` and their bilinear weights in
// its face's texel coordinates; returns how many have a non-zero weight. A
// neighbour beyond the face edge is the texel across it (the point on the
// face's plane at that texel's centre, projected as CubeMap::neighbors does),
// so the blend runs continuously over edges instead of jumping between the
// two faces' edge texels, the faceting interpolation removes; at a corner the
// missing diagonal neighbour becomes one of the three corner texels.
int normal_weights(const CubeMap& normals, const Vec3& normal, int index[4], float weight[4]) {
    const int r = normals.resolution();
    float s, t;
    const int face = CubeMap::face_coordinates(normal, s, t);
    int i0, j0;
    const float wi = axis_weight(s, r, false, i0), wj = axis_weight(t, r, false, j0);
    int count = 0;
    for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
            const float w = (di ? wi : 1.0f - wi) * (dj ? wj : 1.0f - wj);
            if (!(w > 0.0f)) continue;
            const int i = i0 + di, j = j0 + dj;
            if (i >= 0 && i < r && j >= 0 && j < r) {
                index[count] = normals.index(face, i, j);
            } else {
                const float si = -1.0f + (2.0f * float(i) + 1.0f) / float(r), tj = -1.0f + (2.0f * float(j) + 1.0f) / float(r);
                index[count] = normals.index_of(CubeMap::face_direction(face, si, tj));
            }
            weight[count++] = w;
        }
    return count;
}

}  // namespace

size_t SparseVisibility::bytes() const {
    return start.size() * sizeof(uint64_t) + index.size() * sizeof(uint32_t) + value.size() * sizeof(float);
}

TriplePrecompute precompute_triple_visibility(const GroundTruth& truth, const CubeMap& environment,
                                              const TripleOptions& options) {
    const Scene& scene = truth.posed().scene();
    const int n = environment.resolution();
    if (!haar::is_power_of_two(n))
        throw_file_error(scene.source, "the triple product needs a power-of-two cube resolution, the environment has {}", n);
    RSL_CHECK_GE(options.block_vertices, 1);
    const auto wall_start = Clock::now();
    TriplePrecompute pre(VertexLayout{scene});
    pre.environment_rotation = scene.environment.rotation_at(truth.time());
    const TransportSampler sampler(truth, environment, pre.environment_rotation, options.visibility);
    pre.directions = sampler.directions();
    pre.visibility.resolution = n;
    const size_t vertices = pre.layout.total();
    const size_t block_count = (vertices + options.block_vertices - 1) / options.block_vertices;
    std::vector<VisibilityBlock> blocks(block_count);
    std::mutex totals_mutex;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, block_count, 1), [&](const tbb::blocked_range<size_t>& range) {
        TransportSampler::Scratch scratch = sampler.make_scratch();
        std::vector<float> V(size_t(sampler.texel_count())), g(V.size()), haar_scratch(size_t(n) * n);
        double trace_s = 0, transform_s = 0;
        uint64_t rays = 0;
        for (size_t b = range.begin(); b != range.end(); ++b) {
            const size_t first = b * options.block_vertices, last = std::min(vertices, first + options.block_vertices);
            for (size_t v = first; v < last; ++v) {
                auto t0 = Clock::now();
                const auto [part, vertex] = pre.layout.locate(v);
                rays += sampler.sample_visibility(part, vertex, V.data(), scratch);
                trace_s += seconds_since(t0);
                t0 = Clock::now();
                add_visibility_row(V.data(), environment, options.visibility_drop, g, haar_scratch, blocks[b]);
                transform_s += seconds_since(t0);
            }
        }
        std::lock_guard<std::mutex> lock(totals_mutex);
        pre.trace_cpu_seconds += trace_s, pre.transform_cpu_seconds += transform_s, pre.rays += rays;
    });
    const auto join_start = Clock::now();
    join_blocks(blocks, pre.visibility);
    pre.transform_cpu_seconds += seconds_since(join_start);
    pre.wall_seconds = seconds_since(wall_start);
    return pre;
}

// ---------------------------------------------------------------- BRDF slices

void brdf_slice(const Brdf& brdf, const Frame& frame, const Vec3& view_local, const std::vector<Vec3>& directions,
                Color* out) {
    for (size_t k = 0; k < directions.size(); ++k) {
        const Vec3 wi = frame.to_local(directions[k]);
        out[k] = wi.z > 0.0f ? brdf.eval(wi, view_local) * wi.z : Color(0.0f);
    }
}

BrdfSlices::BrdfSlices(const Brdf& brdf, const std::vector<Vec3>& directions, int resolution,
                       const TripleOptions& options)
    : normals_(options.normal_resolution),
      views_(brdf.model() == "lambert" ? 1 : options.view_resolution),  // ρ of a Lambertian BRDF ignores the view
      terms_(std::min(options.brdf_terms, int(directions.size()))), lookup_(options.lookup) {
    RSL_CHECK_GE(options.normal_resolution, 1);
    RSL_CHECK_GE(options.view_resolution, 1);
    RSL_CHECK_GE(options.brdf_terms, 1);
    RSL_CHECK_EQ(int(directions.size()), 6 * resolution * resolution);
    const int slices = normals_.texel_count() * views_ * views_;
    index_.assign(size_t(slices) * terms_, 0);
    value_.assign(size_t(slices) * terms_, Color(0.0f));
    count_.assign(size_t(slices), 0);
    std::mutex seconds_mutex;
    tbb::parallel_for(tbb::blocked_range<int>(0, slices, 16), [&](const tbb::blocked_range<int>& range) {
        const auto start = Clock::now();
        CubeMap slice(resolution);
        haar::LightingApproximation approximation(resolution);
        haar::SparseLighting kept;
        for (int s = range.begin(); s != range.end(); ++s) {
            const Frame frame = Frame::from_normal(normal(s));
            brdf_slice(brdf, frame, view_direction(s % (views_ * views_), views_), directions, slice.radiances().data());
            // The same area-weighted choice as Ng 2003's lighting approximation.
            approximation.approximate(slice, terms_, kept);
            int count = 0;
            for (size_t t = 0; t < kept.size(); ++t) {
                if (kept.value[t] == Color(0.0f)) continue;
                index_[size_t(s) * terms_ + count] = kept.index[t];
                value_[size_t(s) * terms_ + count] = kept.value[t];
                ++count;
            }
            count_[size_t(s)] = count;
        }
        std::lock_guard<std::mutex> lock(seconds_mutex);
        cpu_seconds_ += seconds_since(start);
    });
}

Vec3 BrdfSlices::normal(int slice) const { return normals_.texel_direction(slice / (views_ * views_)); }

Vec3 BrdfSlices::view(int slice) const {
    return Frame::from_normal(normal(slice)).to_world(view_direction(slice % (views_ * views_), views_));
}

int BrdfSlices::slice_of(const Vec3& normal_world, const Vec3& view_world) const {
    const int normal_index = normals_.index_of(normal_world);
    const Frame frame = Frame::from_normal(normals_.texel_direction(normal_index));
    return normal_index * views_ * views_ + view_cell(frame.to_local(view_world), views_);
}

void BrdfSlices::weights(const Vec3& normal_world, const Vec3& view_world, SliceWeights& out) const {
    out.count = 0;
    if (lookup_ == TripleLookup::nearest) {
        out.slice[0] = slice_of(normal_world, view_world), out.weight[0] = 1.0f, out.count = 1;
        return;
    }
    int normal_index[4];
    float normal_weight[4];
    const int normals = normal_weights(normals_, normal_world, normal_index, normal_weight);
    for (int a = 0; a < normals; ++a) {
        // Each tabulated normal's views are in its own frame, so the view is found there.
        const Frame frame = Frame::from_normal(normals_.texel_direction(normal_index[a]));
        const Vec2 coords = view_coords(frame.to_local(view_world));
        int row, column;
        const float wr = axis_weight(coords.x, views_, true, row), wc = axis_weight(coords.y, views_, true, column);
        for (int dr = 0; dr < 2; ++dr)
            for (int dc = 0; dc < 2; ++dc) {
                const float w = normal_weight[a] * (dr ? wr : 1.0f - wr) * (dc ? wc : 1.0f - wc);
                if (!(w > 0.0f)) continue;
                out.slice[out.count] = (normal_index[a] * views_ + row + dr) * views_ + column + dc;
                out.weight[out.count++] = w;
            }
    }
}

size_t BrdfSlices::accumulate(const SliceWeights& weights, Color* dense, uint8_t* touched, int32_t* list,
                              size_t listed) const {
    for (int w = 0; w < weights.count; ++w) {
        const int slice = weights.slice[w];
        const int32_t* index = this->index(slice);
        const Color* value = this->value(slice);
        for (int t = 0; t < count(slice); ++t) {
            const int32_t i = index[t];
            if (!touched[i]) touched[i] = 1, list[listed++] = i;
            dense[i] += weights.weight[w] * value[t];
        }
    }
    return listed;
}

size_t BrdfSlices::bytes() const {
    return index_.size() * sizeof(int32_t) + value_.size() * sizeof(Color) + count_.size() * sizeof(int32_t);
}

size_t TripleBrdfTables::bytes() const {
    size_t total = 0;
    std::vector<const BrdfSlices*> seen;
    for (const auto& table : part)
        if (std::find(seen.begin(), seen.end(), table.get()) == seen.end()) {
            seen.push_back(table.get());
            total += table->bytes();
        }
    return total;
}

double TripleBrdfTables::cpu_seconds() const {
    double total = 0;
    std::vector<const BrdfSlices*> seen;
    for (const auto& table : part)
        if (std::find(seen.begin(), seen.end(), table.get()) == seen.end()) {
            seen.push_back(table.get());
            total += table->cpu_seconds();
        }
    return total;
}

TripleBrdfTables tabulate_part_brdfs(const GroundTruth& truth, const TriplePrecompute& precompute,
                                     const TripleOptions& options) {
    TripleBrdfTables tables;
    std::map<const Brdf*, std::shared_ptr<const BrdfSlices>> by_brdf;
    for (int p = 0; p < precompute.layout.parts(); ++p) {
        const Brdf& brdf = truth.part_unit_texture_brdf(p);
        auto& table = by_brdf[&brdf];
        if (!table)
            table = std::make_shared<BrdfSlices>(brdf, precompute.directions, precompute.visibility.resolution, options);
        tables.part.push_back(table);
    }
    return tables;
}

// ---------------------------------------------------------------- rendering

// Per-thread dense arrays for one vertex's factors (zero between vertices).
struct TripleScratch {
    explicit TripleScratch(int n)
        : visibility(size_t(6) * n * n, 0.0f), brdf(size_t(6) * n * n, Color(0.0f)), brdf_touched(brdf.size(), 0),
          brdf_index(brdf.size()), transform(size_t(n) * n * 3) {}
    std::vector<float> visibility;
    std::vector<Color> brdf;
    std::vector<uint8_t> brdf_touched;  // the blended slice's indices, listed once each in brdf_index
    std::vector<int32_t> brdf_index;
    SliceWeights weights;
    std::vector<float> transform;
};

struct TripleRenderer::State {
    explicit State(int n) : approximation(n), prepared(n), scratch([n] { return TripleScratch(n); }) {}
    haar::LightingApproximation approximation;
    haar::SparseLighting lighting;
    triple::PreparedLighting prepared;
    tbb::enumerable_thread_specific<TripleScratch> scratch;
};

TripleRenderer::TripleRenderer(const TriplePrecompute& precompute, const GroundTruth& truth,
                               const TripleBrdfTables* tables)
    : precompute_(precompute), truth_(truth), tables_(tables),
      state_(std::make_unique<State>(precompute.visibility.resolution)) {
    RSL_CHECK_GT(precompute.visibility.resolution, 0);
    if (tables) RSL_CHECK_EQ(int(tables->part.size()), precompute.layout.parts());
}

TripleRenderer::~TripleRenderer() = default;

namespace {

// Vertex phase: the exact slice of the vertex's own frame and view,
// Haar-transformed per face into `brdf` (dense).
void exact_slice(const Brdf& brdf, const SurfacePoint& x, const Vec3& view_local, const std::vector<Vec3>& directions,
                 int n, TripleScratch& scratch) {
    brdf_slice(brdf, x.frame, view_local, directions, scratch.brdf.data());
    float* data = reinterpret_cast<float*>(scratch.brdf.data());
    for (int face = 0; face < 6; ++face) haar::forward_face(data + size_t(face) * n * n * 3, n, 3, scratch.transform.data());
}

}  // namespace

void TripleRenderer::render(const CubeMap& environment, int terms, const Vec3& camera, std::vector<Color>& out) {
    const int n = precompute_.visibility.resolution;
    RSL_CHECK_EQ(environment.resolution(), n);
    State& state = *state_;
    state.approximation.approximate(environment, terms, state.lighting);
    state.prepared.prepare(state.lighting.index.data(), state.lighting.value.data(), state.lighting.size());
    const SparseVisibility& vis = precompute_.visibility;
    const PosedScene& posed = truth_.posed();
    out.assign(precompute_.layout.total(), Color(0.0f));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
        TripleScratch& scratch = state.scratch.local();
        for (size_t v = range.begin(); v != range.end(); ++v) {
            const auto [part, vertex] = precompute_.layout.locate(v);
            const SurfacePoint x = posed.vertex(part, vertex);
            const Vec3 view = glm::normalize(camera - x.position);
            const Vec3 view_local = x.frame.to_local(view);
            if (!(view_local.z > 0.0f)) continue;  // ρ is 0 for a view below the horizon (Brdf contract)
            triple::Factors factors;
            const uint64_t first = vis.start[v], last = vis.start[v + 1];
            for (uint64_t e = first; e < last; ++e) scratch.visibility[vis.index[e]] = vis.value[e];
            factors.visibility_dense = scratch.visibility.data();
            factors.visibility_index = vis.index.data() + first;
            factors.visibility_count = size_t(last - first);
            factors.brdf_dense = scratch.brdf.data();
            if (tables_) {
                const BrdfSlices& table = *tables_->part[size_t(part)];
                table.weights(x.frame.z, view, scratch.weights);
                factors.brdf_index = scratch.brdf_index.data();
                factors.brdf_count = table.accumulate(scratch.weights, scratch.brdf.data(), scratch.brdf_touched.data(),
                                                      scratch.brdf_index.data(), 0);
            } else {
                exact_slice(truth_.part_unit_texture_brdf(part), x, view_local, precompute_.directions, n, scratch);
            }
            out[v] = triple::evaluate(state.prepared, factors);
            for (uint64_t e = first; e < last; ++e) scratch.visibility[vis.index[e]] = 0.0f;
            for (size_t t = 0; t < factors.brdf_count; ++t) {
                scratch.brdf[factors.brdf_index[t]] = Color(0.0f);
                scratch.brdf_touched[size_t(factors.brdf_index[t])] = 0;
            }
        }
    });
}

}  // namespace rsl
