#include "fields/ovdf.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>

#include <tbb/parallel_for.h>

#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/core/hemisphere.h"
#include "src/trace/ray_scene.h"

namespace rsl {

void Ovdf::prepare() {
    const OvdfParams& p = params;
    RSL_CHECK_GE(p.shells, 2);
    RSL_CHECK_GT(p.inner_radius, 0.0f);
    RSL_CHECK_GT(p.outer_radius, p.inner_radius);
    RSL_CHECK_EQ(p.cube_resolution % p.segments_per_side, 0);
    shell_radii_.resize(p.shells);
    for (int s = 0; s < p.shells; ++s) {
        const float u = float(s) / float(p.shells - 1);
        float r = 0;
        switch (p.spacing) {
            case ShellSpacing::Geometric: r = p.inner_radius * std::pow(p.outer_radius / p.inner_radius, u); break;
            case ShellSpacing::Linear: r = p.inner_radius + (p.outer_radius - p.inner_radius) * u; break;
            case ShellSpacing::InverseRadius:
                r = 1.0f / (1.0f / p.inner_radius + (1.0f / p.outer_radius - 1.0f / p.inner_radius) * u);
                break;
        }
        shell_radii_[s] = r * radius;
    }
    // Face axes from the cube-map convention: face_direction(f, s, t) ∝ N + s·S + t·T.
    const float root2 = std::sqrt(2.0f);
    for (int f = 0; f < 6; ++f) {
        face_normal_[f] = CubeMap::face_direction(f, 0, 0);
        face_s_[f] = root2 * CubeMap::face_direction(f, 1, 0) - face_normal_[f];
        face_t_[f] = root2 * CubeMap::face_direction(f, 0, 1) - face_normal_[f];
        RSL_CHECK_LT(std::abs(glm::dot(face_s_[f], face_normal_[f])), 1e-4f);
    }
    const int n = p.cube_resolution;
    frames_.resize(size_t(6) * n * n);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const float s = -1.0f + (i + 0.5f) * 2.0f / n, t = -1.0f + (j + 0.5f) * 2.0f / n;
                const Vec3 z = -glm::normalize(face_normal_[f] + s * face_s_[f] + t * face_t_[f]);
                frames_[(f * n + j) * n + i] = Frame::from_normal_tangent(z, face_s_[f]);
            }
}

float Ovdf::shell_coordinate(float distance) const {
    const OvdfParams& p = params;
    const float d = distance / radius, last = float(p.shells - 1);
    switch (p.spacing) {
        case ShellSpacing::Geometric:
            return last * std::log(std::max(d, 1e-6f) / p.inner_radius) / std::log(p.outer_radius / p.inner_radius);
        case ShellSpacing::Linear: return last * (d - p.inner_radius) / (p.outer_radius - p.inner_radius);
        case ShellSpacing::InverseRadius:
            return last * (1.0f / std::max(d, 1e-6f) - 1.0f / p.inner_radius) /
                   (1.0f / p.outer_radius - 1.0f / p.inner_radius);
    }
    return 0;
}

int Ovdf::segment_of(int shell, int face, int i, int j) const {
    const int m = params.segments_per_side, n = params.cube_resolution;
    return ((shell * 6 + face) * m + j * m / n) * m + i * m / n;
}

Vec3 Ovdf::sample_position(int shell, int face, int i, int j) const {
    return center - shell_radii_[shell] * sample_frame(face, i, j).z;
}

float Ovdf::sample_distance(int sample, const Vec2& p) const {
    const BilinearTaps taps = bilinear_taps(params.vdt_resolution, p);
    float d = 0;
    for (int k = 0; k < 4; ++k) d += taps.weight[k] * model.reconstruct(sample, taps.index[k]);
    return d;
}

float Ovdf::visible_fraction(const Vec3& point, const Vec3& light, float half_edge, OvdfBlend blend) const {
    return visible_fraction_from_distance(distance(point, light, blend), half_edge);
}

float Ovdf::distance(const Vec3& point, const Vec3& light, OvdfBlend blend) const {
    const Vec3 v = point - center;
    const float d = glm::length(v);
    if (d >= shell_radii_.back()) return kVdtNoBoundaryDistance;  // no shadow beyond the outer shell
    const Vec3 dir = d > 0 ? v / d : Vec3(0, 0, 1);
    const int shells = params.shells, n = params.cube_resolution;
    const float u = std::clamp(shell_coordinate(d), 0.0f, float(shells - 1));  // clamped inside
    const int s0 = std::min(int(u), shells - 2);
    const float fs = u - float(s0);
    // Cube face and bilinear position among the face's sample directions.
    int face = 0;
    float best = -2;
    for (int f = 0; f < 6; ++f) {
        const float c = glm::dot(dir, face_normal_[f]);
        if (c > best) best = c, face = f;
    }
    const float x = std::clamp((glm::dot(dir, face_s_[face]) / best + 1.0f) * 0.5f * n - 0.5f, 0.0f, float(n - 1));
    const float y = std::clamp((glm::dot(dir, face_t_[face]) / best + 1.0f) * 0.5f * n - 0.5f, 0.0f, float(n - 1));
    const int i0 = std::min(int(x), n - 2), j0 = std::min(int(y), n - 2);
    const float fx = x - float(i0), fy = y - float(j0);
    const int ii[4] = {i0, i0 + 1, i0, i0 + 1}, jj[4] = {j0, j0, j0 + 1, j0 + 1};
    const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};

    // The receiver's own pole frame, twisted by the face rule like its samples.
    const Frame aligned = Frame::from_normal_tangent(-dir, face_s_[face]);
    const BilinearTaps taps = bilinear_taps(params.vdt_resolution, lookup_plane_point(aligned.to_local(light)));
    float distance = 0;
    for (int k = 0; k < 2; ++k) {
        const int shell = s0 + k;
        const float ws = k == 0 ? 1.0f - fs : fs;
        if (ws == 0.0f) continue;
        const int segment = segment_of(shell, face, ii[0], jj[0]);
        const bool one_segment = segment == segment_of(shell, face, ii[3], jj[3]);
        if (blend == OvdfBlend::AlignedCoefficients && one_segment && model.vectors <= 32) {
            // Reconstruction is linear in the coefficients, so blending them
            // first equals blending the four reconstructions.
            float coefficients[32] = {};
            for (int q = 0; q < 4; ++q) {
                const float* c = model.coefficients_of(sample_index(shell, face, ii[q], jj[q]));
                for (int m = 0; m < model.vectors; ++m) coefficients[m] += w[q] * c[m];
            }
            float value = 0;
            for (int t = 0; t < 4; ++t) {
                const float* row = model.row(segment, taps.index[t]);
                float r = row[0];
                for (int m = 0; m < model.vectors; ++m) r += coefficients[m] * row[m + 1];
                value += taps.weight[t] * r;
            }
            distance += ws * value;
        } else if (blend != OvdfBlend::SampleFrames) {
            for (int q = 0; q < 4; ++q) {
                if (w[q] == 0.0f) continue;
                const int sample = sample_index(shell, face, ii[q], jj[q]);
                float value = 0;
                for (int t = 0; t < 4; ++t) value += taps.weight[t] * model.reconstruct(sample, taps.index[t]);
                distance += ws * w[q] * value;
            }
        } else {
            for (int q = 0; q < 4; ++q) {
                if (w[q] == 0.0f) continue;
                const Frame& frame = sample_frame(face, ii[q], jj[q]);
                const Vec2 p = lookup_plane_point(frame.to_local(light));
                distance += ws * w[q] * sample_distance(sample_index(shell, face, ii[q], jj[q]), p);
            }
        }
    }
    return distance;
}

Ovdf bake_ovdf(const TriangleMesh& mesh, const OvdfParams& params, OvdfBakeStats* stats,
               const std::function<void(double)>& progress) {
    const auto start = std::chrono::steady_clock::now();
    if (stats) *stats = OvdfBakeStats{};
    Ovdf ovdf;
    ovdf.params = params;
    const BoundingSphere sphere = mesh.bounding_sphere();
    ovdf.center = sphere.center;
    ovdf.radius = std::max(sphere.radius, 1e-6f);
    ovdf.prepare();

    RayScene scene;
    scene.add_instance(scene.add_mesh(mesh), Mat4(1.0f));
    scene.commit();

    // One sampling pattern per shell: rays only towards the part's bounding
    // cone (plus a texel of margin); everything outside it is visible.
    const int nv = params.vdt_resolution, dims = nv * nv;
    const float texel = 2.0f / float(nv);
    std::vector<std::unique_ptr<HemisphereSampling>> samplings;
    for (int s = 0; s < params.shells; ++s) {
        const float ratio = ovdf.radius / ovdf.shell_radius(s);
        float max_radius = 1.5f;  // inside the bounding sphere: the whole square
        if (ratio < 1.0f) {
            const float cone = std::asin(ratio);
            max_radius = std::min(1.5f, std::sqrt(2.0f) * std::sin(0.5f * cone) + 1.5f * texel);
        }
        samplings.push_back(std::make_unique<HemisphereSampling>(nv, params.supersampling, true, max_radius));
    }

    const int n = params.cube_resolution, m = params.segments_per_side, side = n / m;
    const int segments = params.segment_count();
    ovdf.model.dims = dims;
    ovdf.model.vectors = params.vectors;
    ovdf.model.clusters = segments;
    ovdf.model.tables.assign(size_t(segments) * dims * (params.vectors + 1), 0.0f);
    ovdf.model.assignment.assign(params.sample_count(), 0);
    ovdf.model.coefficients.assign(params.sample_count() * params.vectors, 0.0f);
    std::atomic<int> done{0};
    std::mutex stats_mutex;
    tbb::parallel_for(0, segments, [&](int segment) {
        const int si = segment % m, sj = (segment / m) % m, face = (segment / (m * m)) % 6;
        const int shell = segment / (m * m * 6);
        std::vector<int> samples;
        for (int j = sj * side; j < (sj + 1) * side; ++j)
            for (int i = si * side; i < (si + 1) * side; ++i) samples.push_back(ovdf.sample_index(shell, face, i, j));
        std::vector<float> tables(samples.size() * dims);
        VisibilityScratch scratch;
        scratch.coverage.resize(dims);
        for (size_t k = 0; k < samples.size(); ++k) {
            const int i = si * side + int(k) % side, j = sj * side + int(k) / side;
            trace_coverage(scene, *samplings[shell], ovdf.sample_position(shell, face, i, j),
                           ovdf.sample_frame(face, i, j), BelowHorizon::Visible, scratch, scratch.coverage.data());
            compute_vdt(nv, scratch.coverage.data(), tables.data() + k * dims, params.mode, scratch.vdt);
        }
        CpcaModel local;
        local.dims = dims;
        local.vectors = params.vectors;
        std::vector<int> members(samples.size());
        std::iota(members.begin(), members.end(), 0);
        fit_pca_cluster(tables.data(), dims, members, params.vectors, params.seed + uint64_t(segment),
                        params.half_precision_tables, local);
        local.assignment.assign(samples.size(), 0);
        project_coefficients(tables.data(), local);
        std::copy(local.tables.begin(), local.tables.end(),
                  ovdf.model.tables.begin() + size_t(segment) * dims * (params.vectors + 1));
        for (size_t k = 0; k < samples.size(); ++k) {
            ovdf.model.assignment[samples[k]] = segment;
            std::copy(local.coefficients_of(int(k)), local.coefficients_of(int(k)) + params.vectors,
                      ovdf.model.coefficients.begin() + size_t(samples[k]) * params.vectors);
        }
        if (stats) {
            const CpcaReport r = measure_cpca(tables.data(), local, params.half_precision_tables);
            std::lock_guard<std::mutex> lock(stats_mutex);
            stats->compression.rms_error += r.rms_error * r.rms_error * double(samples.size());
            stats->compression.max_error = std::max(stats->compression.max_error, r.max_error);
        }
        const int now = ++done;
        if (progress) progress(double(now) / segments);
    });
    if (stats) {
        stats->compression.rms_error = std::sqrt(stats->compression.rms_error / double(params.sample_count()));
        stats->compression.raw_bytes = params.sample_count() * dims * sizeof(float);
        stats->compression.stored_bytes = ovdf.model.stored_bytes(params.half_precision_tables);
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return ovdf;
}

}  // namespace rsl
