#include "src/fields/ovdf.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>

#include <tbb/parallel_for.h>

#include "src/fields/ovdf_spans.h"
#include "src/fields/solid_pieces.h"
#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/core/hemisphere.h"
#include "src/rays/ray_scene.h"
#include "src/shading/interpolation.h"
#include "src/shading/ovdf_tables.h"
#include "src/shading/ovdf_small_occluder.h"
#include "src/shading/ovdf_inside.h"

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
    shell_zoom_.resize(p.shells);
    for (int s = 0; s < p.shells; ++s) shell_zoom_[s] = ovdf_zoom(shell_radii_[s], radius);
    // Face axes from the cube-map convention: face_direction(f, s, t) ∝ N + s·S + t·T.
    const float root2 = std::sqrt(2.0f);
    for (int f = 0; f < 6; ++f) {
        face_normal_[f] = CubeMap::face_direction(f, 0, 0);
        face_s_[f] = root2 * CubeMap::face_direction(f, 1, 0) - face_normal_[f];
        face_t_[f] = root2 * CubeMap::face_direction(f, 0, 1) - face_normal_[f];
        RSL_CHECK_LT(std::abs(glm::dot(face_s_[f], face_normal_[f])), 1e-4f);
    }
    const int n = p.cube_resolution;
    segment_column_.resize(size_t(n));
    for (int i = 0; i < n; ++i) segment_column_[size_t(i)] = i * p.segments_per_side / n;
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
    return shading::ovdf_shell_coordinate(int(p.spacing), p.shells, p.inner_radius, p.outer_radius, distance / radius);
}

Vec3 Ovdf::sample_position(int shell, int face, int i, int j) const {
    return center - shell_radii_[shell] * sample_frame(face, i, j).z;
}

float Ovdf::sample_distance(int sample, const Vec2& p) const {
    const int n = params.cube_resolution;
    const OvdfZoom& zoom = shell_zoom_[sample / (shading::kCubeFaces * n * n)];
    const BilinearTaps taps = bilinear_taps(params.vdt_resolution, zoom.zoom * p);
    float d = 0;
    for (int k = 0; k < 4; ++k) d += taps.weight[k] * model.reconstruct(sample, taps.index[k]);
    return ovdf_plane_distance(d, zoom, glm::length(p));
}

float Ovdf::visible_fraction(const Vec3& point, const Vec3& light, float half_edge, OvdfBlend blend) const {
    const float d = glm::length(point - center);
    if (d >= shell_radii_.back()) return 1.0f;  // no shadow beyond the outer shell
    const OvdfLocation at = locate(point, d);
    if (d < radius && receiver_inside(point, d, at)) return 0.0f;
    const float area = occluded_area_at(at);
    // A part whose bounding cone is narrower than the square: the small-occluder rule.
    const float cone = ovdf_zoom(d, radius).cone;
    const float w = shading::ovdf_small_occluder_weight(cone, half_edge, area);
    const float small =
        w > 0.0f ? shading::ovdf_small_occluder_fraction(shading::ovdf_pole_radial(glm::dot(light, at.aligned.z)), area,
                                                        cone, half_edge)
                 : 1.0f;
    if (w >= 1.0f) return small;
    // Else the straight-edge rule, bounded by the silhouette's area.
    const float fraction = visible_fraction_from_distance(located_distance(at, d, light, blend), half_edge);
    return shading::ovdf_fade_small_occluder(shading::ovdf_area_bound(fraction, area, half_edge), small, w);
}

OvdfLocation Ovdf::locate(const Vec3& point, float d) const {
    OvdfLocation at;
    const Vec3 dir = d > 0 ? (point - center) * (1.0f / d) : Vec3(0, 0, 1);
    const shading::LerpPair shells = shading::ovdf_shell_pair(shell_coordinate(d), params.shells);  // clamped inside
    at.s0 = shells.lower;
    at.fs = shells.upper_weight;
    // Cube face and bilinear position among the face's sample directions.
    const shading::CubeFace face = shading::cube_face(dir, face_normal_.data());
    at.face = face.face;
    const shading::SampleTaps taps =
        shading::ovdf_sample_taps(dir, face.cosine, face_s_[at.face], face_t_[at.face], params.cube_resolution);
    at.ii = taps.i, at.jj = taps.j, at.w = taps.weight;
    // The receiver's own pole frame, twisted by the face rule like its samples.
    at.aligned = Frame::from_normal_tangent(-dir, face_s_[at.face]);
    return at;
}

float Ovdf::blend_samples(const std::vector<float>& per_sample, const OvdfLocation& at) const {
    float blended = 0;
    for (int k = 0; k < 2; ++k) {
        const float ws = k == 0 ? 1.0f - at.fs : at.fs;
        if (ws == 0.0f) continue;
        float value = 0;
        for (int q = 0; q < 4; ++q)
            value += at.w[q] * per_sample[size_t(sample_index(at.s0 + k, at.face, at.ii[q], at.jj[q]))];
        blended += ws * value;
    }
    return blended;
}

float Ovdf::occluded_area_at(const OvdfLocation& at) const {
    return occluded_area.empty() ? shading::kOvdfNoAreaBound : blend_samples(occluded_area, at);
}

float Ovdf::surface_distance_at(const OvdfLocation& at) const {
    return surface_distance.empty() ? 1.0f : blend_samples(surface_distance, at);
}

bool Ovdf::receiver_inside(const Vec3& point, float d, const OvdfLocation& at) const {
    if (!radial_span.empty() && d > 0.0f) {
        const shading::SpanTaps taps = shading::ovdf_span_taps(point - center, span_resolution);
        Vec2 span(0.0f);
        for (int q = 0; q < 4; ++q)
            span += taps.weight[q] * Vec2(radial_span[size_t(2 * taps.index[q])], radial_span[size_t(2 * taps.index[q] + 1)]);
        const int decided = shading::ovdf_span_inside(d, span, radius);
        if (decided >= 0) return decided == 1;
    }
    return shading::ovdf_inside_part(radius, surface_distance_at(at));
}

float Ovdf::distance(const Vec3& point, const Vec3& light, OvdfBlend blend) const {
    const float d = glm::length(point - center);
    if (d >= shell_radii_.back()) return kVdtNoBoundaryDistance;  // no shadow beyond the outer shell
    const OvdfLocation at = locate(point, d);
    if (d < radius && receiver_inside(point, d, at)) return -kVdtNoBoundaryDistance;
    return located_distance(at, d, light, blend);
}

float Ovdf::located_distance(const OvdfLocation& at, float d, const Vec3& light, OvdfBlend blend) const {
    const int s0 = at.s0, face = at.face;
    const float fs = at.fs;
    const glm::ivec4& ii = at.ii;
    const glm::ivec4& jj = at.jj;
    const Vec4& w = at.w;
    const Frame& aligned = at.aligned;
    const Vec2 plane = lookup_plane_point(aligned.to_local(light));
    const float radial = glm::length(plane);
    float distance = 0;
    for (int k = 0; k < 2; ++k) {
        const int shell = s0 + k;
        const float ws = k == 0 ? 1.0f - fs : fs;
        if (ws == 0.0f) continue;
        const OvdfZoom& zoom = shell_zoom_[shell];
        const BilinearTaps taps = bilinear_taps(params.vdt_resolution, zoom.zoom * plane);
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
            distance += ws * ovdf_plane_distance(value, zoom, radial);
        } else if (blend != OvdfBlend::SampleFrames) {
            float blended = 0;  // table units: the bound applies to the shell's blend, as above
            for (int q = 0; q < 4; ++q) {
                if (w[q] == 0.0f) continue;
                const int sample = sample_index(shell, face, ii[q], jj[q]);
                float value = 0;
                for (int t = 0; t < 4; ++t) value += taps.weight[t] * model.reconstruct(sample, taps.index[t]);
                blended += w[q] * value;
            }
            distance += ws * ovdf_plane_distance(blended, zoom, radial);
        } else {
            for (int q = 0; q < 4; ++q) {
                if (w[q] == 0.0f) continue;
                const Frame& frame = sample_frame(face, ii[q], jj[q]);
                const Vec2 p = lookup_plane_point(frame.to_local(light));
                distance += ws * w[q] * sample_distance(sample_index(shell, face, ii[q], jj[q]), p);
            }
        }
    }
    // The part lies in the bounding cone seen from the point itself, tighter
    // than the outer shell's and exact: lights beyond it are unshadowed.
    return shading::ovdf_receiver_distance(distance, radial, ovdf_zoom(d, radius).cone);
}

namespace {

// Local ray directions of one shell's zoomed table: table point p′ looks
// along plane_to_hemisphere(p′ / zoom). Texels beyond the traced radius are
// visible; texels whose center ray differs from a 4-neighbour's get k×k rays.
struct ZoomedSampling {
    int n = 0, k = 1;
    std::vector<int> traced;           // texels with a center ray
    std::vector<Vec3> centers;         // per traced texel
    std::vector<Vec3> subsamples;      // per texel k×k (filled for traced texels)
};

ZoomedSampling zoomed_sampling(int n, int k, const OvdfZoom& zoom) {
    ZoomedSampling z;
    z.n = n, z.k = k;
    const float texel = 2.0f / float(n);
    // Inside the bounding sphere (no cone) the whole square, √2 and beyond included.
    const float max_radius = zoom.cone >= kOvdfNoCone ? 1.5f : std::min(1.5f, zoom.zoom * zoom.cone + 1.5f * texel);
    const auto direction = [&](float x, float y) { return plane_to_hemisphere(Vec2(x, y) / zoom.zoom); };
    z.subsamples.resize(size_t(n) * n * k * k);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = -1.0f + (i + 0.5f) * texel, y = -1.0f + (j + 0.5f) * texel;
            if (x * x + y * y > max_radius * max_radius) continue;
            const int t = j * n + i;
            z.traced.push_back(t);
            z.centers.push_back(direction(x, y));
            for (int b = 0; b < k; ++b)
                for (int a = 0; a < k; ++a)
                    z.subsamples[size_t(t) * k * k + b * k + a] =
                        direction(-1.0f + (i + (a + 0.5f) / k) * texel, -1.0f + (j + (b + 0.5f) / k) * texel);
        }
    return z;
}

struct ZoomedScratch {
    std::vector<Vec3> world_dirs;
    std::vector<uint8_t> hits;
    std::vector<int> boundary;
    std::vector<float> coverage;
    VdtWorkspace vdt;
};

// Coverage (visible fractions) of the zoomed table seen from `origin` in `frame`.
void trace_zoomed_coverage(const RayScene& scene, const ZoomedSampling& z, const Vec3& origin, const Frame& frame,
                           ZoomedScratch& scratch) {
    constexpr float kFar = 1e30f;
    const int n = z.n, kk = z.k * z.k, count = int(z.traced.size());
    std::fill(scratch.coverage.begin(), scratch.coverage.end(), 1.0f);
    scratch.world_dirs.resize(std::max<size_t>(count, size_t(count) * kk));
    scratch.hits.resize(scratch.world_dirs.size());
    for (int c = 0; c < count; ++c) scratch.world_dirs[c] = frame.to_world(z.centers[c]);
    scene.occluded_batch(origin, scratch.world_dirs.data(), count, 0.0f, kFar, scratch.hits.data());
    for (int c = 0; c < count; ++c) scratch.coverage[z.traced[c]] = scratch.hits[c] ? 1.0f : 0.0f;
    if (kk == 1) return;
    scratch.boundary.clear();
    for (int t : z.traced) {
        const int i = t % n, j = t / n;
        const float v = scratch.coverage[t];
        const auto differs = [&](int s) { return scratch.coverage[s] != v; };
        if ((i > 0 && differs(t - 1)) || (i + 1 < n && differs(t + 1)) || (j > 0 && differs(t - n)) ||
            (j + 1 < n && differs(t + n)))
            scratch.boundary.push_back(t);
    }
    int total = 0;
    for (int t : scratch.boundary)
        for (int s = 0; s < kk; ++s) scratch.world_dirs[total++] = frame.to_world(z.subsamples[size_t(t) * kk + s]);
    scene.occluded_batch(origin, scratch.world_dirs.data(), total, 0.0f, kFar, scratch.hits.data());
    for (size_t b = 0; b < scratch.boundary.size(); ++b) {
        int visible = 0;
        for (int s = 0; s < kk; ++s) visible += scratch.hits[b * kk + s];
        scratch.coverage[scratch.boundary[b]] = float(visible) / float(kk);
    }
}

// Where a shell sample traces its table from, and its signed distance to the
// surface. A sample inside the part would see nothing but the part's inside —
// a fully shadowed table that, blended with its neighbours, blackens receivers
// just outside the surface (parts meeting at joints). It traces instead from
// the first point outside along its outward radial line (the same pole and
// zoom): the view a receiver near that surface actually has. Its distance is
// the nearest probe hit, capped at R, negative inside.
struct SampleOrigin {
    Vec3 position;
    float surface_distance;
};
SampleOrigin sample_origin(const SolidPieces& pieces, const Vec3& position, const Vec3& outward, float radius) {
    SampleOrigin origin{position, radius};
    SolidPieces::Probe probe = pieces.probe(position);
    if (!probe.inside) {
        origin.surface_distance = std::min(probe.nearest, radius);
        return origin;
    }
    origin.surface_distance = -std::min(probe.nearest, radius);
    for (int layer = 0; layer < 8 && probe.inside; ++layer) {
        const RayHit exit = pieces.whole().intersect(origin.position, outward);
        if (!exit.hit) break;
        origin.position += (exit.t + 1e-3f * radius) * outward;
        probe = pieces.probe(origin.position);
    }
    return origin;
}

}  // namespace

OvdfParams ovdf_params_for_mesh(OvdfParams params, const TriangleMesh& mesh) {
    constexpr float kSolidCentre = 0.4f, kOpenCentre = 0.03f;
    if (params.inner_radius != 0.0f) return params;
    params.inner_radius = kSolidCentre;
    const Vec3 centre = mesh.bounding_sphere().center;
    if (mesh.triangle_count() == 0 || SolidPieces(mesh, centre).inside(centre)) return params;
    if (params.spacing != ShellSpacing::Geometric || params.shells < 2 || !(params.outer_radius > kSolidCentre)) {
        params.inner_radius = kOpenCentre;
        return params;
    }
    const double ratio = std::pow(double(params.outer_radius) / kSolidCentre, 1.0 / double(params.shells - 1));
    constexpr int kMostShells = 256;  // what a field file holds
    const int inward = std::min(kMostShells - params.shells,
                                int(std::ceil(std::log(double(kSolidCentre) / kOpenCentre) / std::log(ratio) - 1e-9)));
    params.shells += inward;
    params.inner_radius = float(kSolidCentre / std::pow(ratio, double(inward)));
    return params;
}

Ovdf bake_ovdf(const TriangleMesh& mesh, const OvdfParams& requested, OvdfBakeStats* stats,
               const std::function<void(double)>& progress) {
    const OvdfParams params = ovdf_params_for_mesh(requested, mesh);
    const auto start = std::chrono::steady_clock::now();
    if (stats) *stats = OvdfBakeStats{};
    Ovdf ovdf;
    ovdf.params = params;
    const BoundingSphere sphere = mesh.bounding_sphere();
    ovdf.center = sphere.center;
    ovdf.radius = std::max(sphere.radius, 1e-6f);
    ovdf.prepare();

    // The mesh for rays, and its closed pieces for the samples' inside test.
    const SolidPieces pieces(mesh);
    const RayScene& scene = pieces.whole();
    ovdf.span_resolution = shading::kOvdfSpanResolution;
    ovdf.radial_span = bake_radial_spans(pieces, ovdf.center, ovdf.radius, ovdf.span_resolution);

    // One sampling pattern per shell, over its zoomed table: rays only
    // towards the part's bounding cone (plus a texel and a half of margin);
    // everything outside it is visible.
    const int nv = params.vdt_resolution, dims = nv * nv;
    std::vector<ZoomedSampling> samplings;
    for (int s = 0; s < params.shells; ++s)
        samplings.push_back(zoomed_sampling(nv, params.supersampling, ovdf.shell_zoom(s)));

    const int n = params.cube_resolution, m = params.segments_per_side, side = n / m;
    const int segments = params.segment_count();
    ovdf.model.dims = dims;
    ovdf.model.vectors = params.vectors;
    ovdf.model.clusters = segments;
    ovdf.model.tables.assign(size_t(segments) * dims * (params.vectors + 1), 0.0f);
    ovdf.model.assignment.assign(params.sample_count(), 0);
    ovdf.surface_distance.assign(params.sample_count(), 0.0f);
    ovdf.occluded_area.assign(params.sample_count(), 0.0f);
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
        ZoomedScratch scratch;
        scratch.coverage.resize(dims);
        for (size_t k = 0; k < samples.size(); ++k) {
            const int i = si * side + int(k) % side, j = sj * side + int(k) / side;
            const Frame& frame = ovdf.sample_frame(face, i, j);
            SampleOrigin origin{ovdf.sample_position(shell, face, i, j), ovdf.shell_radius(shell) - ovdf.radius};
            if (ovdf.shell_radius(shell) < ovdf.radius)  // beyond the bounding sphere nothing is inside
                origin = sample_origin(pieces, origin.position, -frame.z, ovdf.radius);
            ovdf.surface_distance[ovdf.sample_index(shell, face, i, j)] = origin.surface_distance;
            trace_zoomed_coverage(scene, samplings[shell], origin.position, frame, scratch);
            compute_vdt(nv, scratch.coverage.data(), tables.data() + k * dims, params.mode, scratch.vdt);
            double shadowed = 0;  // texels' shadowed fractions: table units of (2/nv)² each
            for (const float visible : scratch.coverage) shadowed += 1.0 - double(visible);
            const float zoom = ovdf.shell_zoom(shell).zoom, texel = 2.0f / float(nv);
            ovdf.occluded_area[ovdf.sample_index(shell, face, i, j)] = float(shadowed) * texel * texel / (zoom * zoom);
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
