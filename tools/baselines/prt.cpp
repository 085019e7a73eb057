// SH and Haar PRT: one pass of shadow rays over the vertices feeds both
// projections; per-frame rendering is a dot product (SH) or a sparse walk of
// the kept lighting terms' rows (Haar).
#include "tools/baselines/prt.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "tools/baselines/thread_seconds.h"

namespace rsl {

namespace {

using baselines_timing::Clock;
using baselines_timing::seconds_since;

// Builds one block's rows from per-vertex sparse coefficient lists.
struct HaarBlockBuilder {
    std::vector<uint32_t> wavelet;  // per entry
    std::vector<uint16_t> vertex;
    std::vector<Color> value;

    void add_vertex(int local_vertex, const float* coefficients, int count, float drop) {
        float largest = 0.0f;
        for (int k = 0; k < 3 * count; ++k) largest = std::max(largest, std::abs(coefficients[k]));
        const float threshold = largest * drop;
        for (int k = 0; k < count; ++k) {
            const float* c = coefficients + 3 * k;
            const float magnitude = std::max(std::abs(c[0]), std::max(std::abs(c[1]), std::abs(c[2])));
            if (!(magnitude > threshold) || magnitude == 0.0f) continue;
            wavelet.push_back(uint32_t(k));
            vertex.push_back(uint16_t(local_vertex));
            value.push_back(Color(c[0], c[1], c[2]));
        }
    }
    // Counting sort by wavelet index into CSR rows.
    void finish(HaarBlock& block, int wavelets) const {
        block.row_start.assign(size_t(wavelets) + 1, 0);
        for (uint32_t w : wavelet) ++block.row_start[w + 1];
        for (int w = 0; w < wavelets; ++w) block.row_start[w + 1] += block.row_start[w];
        std::vector<uint32_t> cursor(block.row_start.begin(), block.row_start.end() - 1);
        block.vertex.resize(wavelet.size());
        block.value.resize(wavelet.size());
        for (size_t e = 0; e < wavelet.size(); ++e) {
            const uint32_t at = cursor[wavelet[e]]++;
            block.vertex[at] = vertex[e];  // vertices stay in increasing order within a row
            block.value[at] = value[e];
        }
    }
};


// Checking phase: Haar's power-of-two resolution and the block size.
void check_prt_options(const Scene& scene, int n, const PrtOptions& options) {
    if (options.haar && !haar::is_power_of_two(n))
        throw_file_error(scene.source, "Haar PRT needs a power-of-two cube resolution, the environment has {}", n);
    RSL_CHECK_GE(options.block_vertices, 1);
    RSL_CHECK_LE(options.block_vertices, 65536);
}

// Block phase: the block of vertices [first, last) gets its rows from the builder.
void finish_haar_block(const HaarBlockBuilder& builder, size_t first, size_t last, int texels, HaarBlock& block) {
    block.first_vertex = first;
    block.vertex_count = int(last - first);
    builder.finish(block, texels);
}

// Set-up phase: sizes the outputs that `options` asks for (SH coefficients,
// texel sums, Haar blocks); returns the SH texel basis, timed, when SH is on.
std::unique_ptr<sh::TexelBasis> prepare_outputs(PrtPrecompute& prt, const PrtOptions& options, int n,
                                                size_t vertices, size_t block_count) {
    std::unique_ptr<sh::TexelBasis> basis;
    if (options.sh) {
        const auto start = Clock::now();
        basis = std::make_unique<sh::TexelBasis>(n, options.sh_order);
        prt.sh_cpu_seconds += seconds_since(start);
        prt.sh.order = options.sh_order;
        prt.sh.rgb.assign(vertices * sh::coefficient_count(options.sh_order) * 3, 0.0f);
    }
    if (options.check_lighting) {
        RSL_CHECK_EQ(options.check_lighting->resolution(), n);
        prt.texel_sum.assign(vertices, Color(0.0f));
    }
    if (options.haar) {
        prt.haar.resolution = n;
        prt.haar.blocks.resize(block_count);
    }
    return basis;
}

// Vertex phase: Σ_k L_k f_k Ω_k of one vertex's transport f under `lighting`.
Color lit_texel_sum(const CubeMap& lighting, const CubeMap& environment, const std::vector<Color>& f, int texels) {
    DVec3 sum(0.0);
    for (int k = 0; k < texels; ++k)
        sum += DVec3(lighting.radiance(k) * f[k]) * double(environment.solid_angle(k));
    return Color(sum);
}

// Vertex phase: T_i = Σ_k f_k A_ki over the texels with nonzero transport,
// added to the vertex's SH coefficients T.
void project_on_sh(const std::vector<Color>& f, int texels, const sh::TexelBasis& basis, int coefficients, float* T) {
    for (int k = 0; k < texels; ++k) {
        const Color fk = f[k];
        if (fk.r == 0.0f && fk.g == 0.0f && fk.b == 0.0f) continue;
        const float* a = basis.texel(k);
        for (int i = 0; i < coefficients; ++i) {
            T[3 * i] += fk.r * a[i];
            T[3 * i + 1] += fk.g * a[i];
            T[3 * i + 2] += fk.b * a[i];
        }
    }
}

// Vertex phase: the transport times the texels' solid angles, Haar-transformed
// per face into g, and its kept coefficients added to the block's builder.
void add_haar_vertex(const std::vector<Color>& f, const CubeMap& environment, int n, int texels, int local_vertex,
                     float drop, std::vector<float>& g, std::vector<float>& haar_scratch, HaarBlockBuilder& builder) {
    for (int k = 0; k < texels; ++k) {
        const Color gk = f[k] * environment.solid_angle(k);
        g[3 * k] = gk.r, g[3 * k + 1] = gk.g, g[3 * k + 2] = gk.b;
    }
    for (int face = 0; face < 6; ++face)
        haar::forward_face(g.data() + size_t(face) * n * n * 3, n, 3, haar_scratch.data());
    builder.add_vertex(local_vertex, g.data(), texels, drop);
}

}  // namespace

size_t HaarTransport::entries() const {
    size_t total = 0;
    for (const HaarBlock& b : blocks) total += b.value.size();
    return total;
}

size_t HaarTransport::bytes() const {
    size_t total = 0;
    for (const HaarBlock& b : blocks)
        total += b.row_start.size() * sizeof(uint32_t) + b.vertex.size() * sizeof(uint16_t) +
                 b.value.size() * sizeof(Color);
    return total;
}

PrtPrecompute precompute_prt(const GroundTruth& truth, const CubeMap& environment, const PrtOptions& options) {
    const Scene& scene = truth.posed().scene();
    const int n = environment.resolution();
    check_prt_options(scene, n, options);
    const auto wall_start = Clock::now();

    PrtPrecompute prt(VertexLayout{scene});
    prt.time = truth.time();
    prt.environment_rotation = scene.environment.rotation_at(truth.time());
    const TransportSampler sampler(truth, environment, prt.environment_rotation, options.visibility);
    const int texels = sampler.texel_count();
    const size_t vertices = prt.layout.total();

    const size_t block_count = (vertices + options.block_vertices - 1) / options.block_vertices;
    const std::unique_ptr<sh::TexelBasis> basis = prepare_outputs(prt, options, n, vertices, block_count);

    std::mutex totals_mutex;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, block_count, 1), [&](const tbb::blocked_range<size_t>& range) {
        TransportSampler::Scratch scratch = sampler.make_scratch();
        std::vector<Color> f(static_cast<size_t>(texels));
        std::vector<float> g(size_t(texels) * 3), haar_scratch(size_t(n) * n * 3);
        const int coefficients = options.sh ? sh::coefficient_count(options.sh_order) : 0;
        double trace_s = 0, sh_s = 0, haar_s = 0;
        uint64_t rays = 0;
        for (size_t b = range.begin(); b != range.end(); ++b) {
            const size_t first = b * options.block_vertices;
            const size_t last = std::min(vertices, first + options.block_vertices);
            HaarBlockBuilder builder;
            for (size_t v = first; v < last; ++v) {
                auto t0 = Clock::now();
                const auto [part, vertex] = prt.layout.locate(v);
                rays += sampler.sample(part, vertex, f.data(), scratch);
                trace_s += seconds_since(t0);
                if (options.check_lighting)
                    prt.texel_sum[v] = lit_texel_sum(*options.check_lighting, environment, f, texels);
                if (options.sh) {
                    t0 = Clock::now();
                    project_on_sh(f, texels, *basis, coefficients, &prt.sh.rgb[v * coefficients * 3]);
                    sh_s += seconds_since(t0);
                }
                if (options.haar) {
                    t0 = Clock::now();
                    add_haar_vertex(f, environment, n, texels, int(v - first), options.haar_drop, g, haar_scratch,
                                    builder);
                    haar_s += seconds_since(t0);
                }
            }
            if (options.haar) {
                const auto t0 = Clock::now();
                finish_haar_block(builder, first, last, texels, prt.haar.blocks[b]);
                haar_s += seconds_since(t0);
            }
        }
        std::lock_guard<std::mutex> lock(totals_mutex);
        prt.trace_cpu_seconds += trace_s;
        prt.sh_cpu_seconds += sh_s;
        prt.haar_cpu_seconds += haar_s;
        prt.rays += rays;
    });
    prt.wall_seconds = seconds_since(wall_start);
    return prt;
}

// ---------------------------------------------------------------- SH rendering

ShRenderer::ShRenderer(const PrtPrecompute& prt, const CubeMap& environment) : prt_(prt) {
    RSL_CHECK_GT(prt.sh.order, 0);
    lighting_ = sh::project_cube(environment, sh::TexelBasis(environment.resolution(), prt.sh.order));
}

void ShRenderer::render(int order, const Mat3& rotation, std::vector<Color>& out) const {
    RSL_CHECK_GE(order, 1);
    RSL_CHECK_LE(order, prt_.sh.order);
    const int coefficients = sh::coefficient_count(order), stride = sh::coefficient_count(prt_.sh.order);
    // Lighting in the transport's frame: turned by R0⁻¹ R (R0: precompute rotation).
    const glm::dmat3 relative = glm::transpose(glm::dmat3(prt_.environment_rotation)) * glm::dmat3(rotation);
    sh::ShColor light{order, std::vector<double>(lighting_.rgb.begin(), lighting_.rgb.begin() + 3 * coefficients)};
    light = sh::Rotation(order, relative).apply(light);
    float l[3 * sh::kMaxOrder * sh::kMaxOrder];
    for (int i = 0; i < 3 * coefficients; ++i) l[i] = float(light.rgb[i]);
    const size_t vertices = prt_.layout.total();
    out.resize(vertices);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 1024), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t v = range.begin(); v != range.end(); ++v) {
            const float* T = &prt_.sh.rgb[v * stride * 3];
            float r = 0, g = 0, b = 0;
            for (int i = 0; i < coefficients; ++i) {
                r += T[3 * i] * l[3 * i];
                g += T[3 * i + 1] * l[3 * i + 1];
                b += T[3 * i + 2] * l[3 * i + 2];
            }
            out[v] = Color(r, g, b);
        }
    });
}

// ---------------------------------------------------------------- Haar rendering

HaarRenderer::HaarRenderer(const PrtPrecompute& prt) : prt_(prt), approximation_(prt.haar.resolution) {
    RSL_CHECK_GT(prt.haar.resolution, 0);
}

void HaarRenderer::render(const CubeMap& environment, int terms, std::vector<Color>& out) {
    approximation_.approximate(environment, terms, lighting_);
    out.assign(prt_.layout.total(), Color(0.0f));
    const auto& blocks = prt_.haar.blocks;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t b = range.begin(); b != range.end(); ++b) {
            const HaarBlock& block = blocks[b];
            Color* result = out.data() + block.first_vertex;
            for (size_t t = 0; t < lighting_.size(); ++t) {
                const uint32_t row = uint32_t(lighting_.index[t]);
                const Color L = lighting_.value[t];
                for (uint32_t e = block.row_start[row]; e < block.row_start[row + 1]; ++e)
                    result[block.vertex[e]] += L * block.value[e];
            }
        }
    });
}

}  // namespace rsl
