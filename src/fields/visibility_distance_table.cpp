#include "src/fields/visibility_distance_table.h"

#include <cmath>
#include <limits>

#include "src/core/error.h"

namespace rsl {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Felzenszwalb–Huttenlocher 1D transform over the finite entries of f:
// dist2[q] = min_p (q − p)² + f[p] and arg[q] the minimizing p (−1 when f has
// no finite entry). v and z hold the lower envelope (sizes n and n + 1).
void lower_envelope_1d(const float* f, int n, int stride_out, float* dist2, int* arg, int* v, float* z) {
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == kInf) continue;
        if (k < 0) {
            k = 0;
            v[0] = q;
            z[0] = -kInf;
            z[1] = kInf;
            continue;
        }
        const float fq = f[q] + float(q) * float(q);
        float s = (fq - (f[v[k]] + float(v[k]) * float(v[k]))) / (2.0f * float(q - v[k]));
        while (s <= z[k]) {  // z[0] = −∞ stops this at k = 0
            --k;
            s = (fq - (f[v[k]] + float(v[k]) * float(v[k]))) / (2.0f * float(q - v[k]));
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = kInf;
    }
    if (k < 0) {
        for (int q = 0; q < n; ++q) {
            dist2[q * stride_out] = kInf;
            arg[q * stride_out] = -1;
        }
        return;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < float(q)) ++k;
        const float d = float(q - v[k]);
        dist2[q * stride_out] = d * d + f[v[k]];
        arg[q * stride_out] = v[k];
    }
}

// Exact squared Euclidean distance (texel units) from every texel center to the
// nearest site center, and that site's index (site_of, −1 when there is none).
void feature_transform(int n, const uint8_t* is_site, float* dist2, int* site_of, VdtWorkspace& ws) {
    float* f = ws.parabola_f.data();
    int* v = ws.envelope_v.data();
    float* z = ws.envelope_z.data();
    // Columns: distance along j to the nearest site in the same column.
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) f[j] = is_site[j * n + i] ? 0.0f : kInf;
        lower_envelope_1d(f, n, n, ws.column_dist2.data() + i, ws.column_site.data() + i, v, z);
    }
    // Rows: combine columns.
    for (int j = 0; j < n; ++j) {
        const float* g = ws.column_dist2.data() + j * n;
        int* arg = site_of + j * n;
        lower_envelope_1d(g, n, 1, dist2 + j * n, arg, v, z);
        for (int i = 0; i < n; ++i) {
            const int column = arg[i];
            arg[i] = column < 0 ? -1 : ws.column_site[j * n + column] * n + column;
        }
    }
}

// Distance (texel units) from a texel center to a straight edge crossing the
// texel, from the texel's coverage a and the coverage gradient (gx, gy), which
// gives the edge's orientation (Gustavson & Strand's edgedf). Positive when
// a < ½, i.e. when the center lies on the uncovered side.
float edge_offset_from_coverage(float gx, float gy, float a) {
    if (gx == 0.0f || gy == 0.0f) return 0.5f - a;  // axis-aligned (or unknown) edge
    const float length = std::sqrt(gx * gx + gy * gy);
    gx = std::abs(gx / length);
    gy = std::abs(gy / length);
    if (gx < gy) std::swap(gx, gy);
    const float a1 = 0.5f * gy / gx;
    if (a < a1) return 0.5f * (gx + gy) - std::sqrt(2.0f * gx * gy * a);
    if (a < 1.0f - a1) return (0.5f - a) * gx;
    return -0.5f * (gx + gy) + std::sqrt(2.0f * gx * gy * (1.0f - a));
}

}  // namespace

void VdtWorkspace::reserve(int n) {
    const size_t nn = size_t(n) * n;
    if (column_dist2.size() >= nn) return;
    column_dist2.resize(nn);
    column_site.resize(nn);
    site_of.resize(nn);
    offset.resize(nn);
    is_site.resize(nn);
    parabola_f.resize(n);
    envelope_v.resize(n);
    envelope_z.resize(n + 1);
}

void compute_vdt(int n, const float* coverage, float* vdt, VdtMode mode, VdtWorkspace& ws) {
    RSL_CHECK_GE(n, 2);
    ws.reserve(n);
    const int nn = n * n;
    const float texel = 2.0f / float(n);
    auto visible = [&](int t) { return coverage[t] >= 0.5f; };
    float* dist2 = ws.offset.data();  // reused as scratch in binary mode
    uint8_t* site = ws.is_site.data();

    if (mode == VdtMode::Binary) {
        // Visible texels: distance to the nearest blocked center − ½; and vice versa.
        for (int pass = 0; pass < 2; ++pass) {
            const bool measuring_visible = pass == 0;
            for (int t = 0; t < nn; ++t) site[t] = visible(t) != measuring_visible;
            feature_transform(n, site, dist2, ws.site_of.data(), ws);
            for (int t = 0; t < nn; ++t) {
                if (visible(t) != measuring_visible) continue;
                const float d = dist2[t] == kInf ? kVdtNoBoundaryDistance : (std::sqrt(dist2[t]) - 0.5f) * texel;
                vdt[t] = measuring_visible ? d : -d;
            }
        }
        return;
    }

    // Coverage-aware: sites are the texels holding the boundary.
    auto cov = [&](int i, int j) {
        i = std::clamp(i, 0, n - 1);
        j = std::clamp(j, 0, n - 1);
        return coverage[j * n + i];
    };
    float* offset = ws.offset.data();
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int t = j * n + i;
            const float a = coverage[t];
            RSL_CHECK(a >= 0.0f && a <= 1.0f);
            const bool fractional = a > 0.0f && a < 1.0f;
            if (!fractional) {
                // A pure texel holds the boundary only where it touches a pure
                // texel of the other value: then the edge runs along their
                // shared side, ½ texel from the center. Next to a fractional
                // texel the edge lies inside that texel instead.
                auto opposite_pure = [&](int s) { return coverage[s] == 1.0f - a; };
                site[t] = (i > 0 && opposite_pure(t - 1)) || (i + 1 < n && opposite_pure(t + 1)) ||
                          (j > 0 && opposite_pure(t - n)) || (j + 1 < n && opposite_pure(t + n));
                offset[t] = a - 0.5f;
                continue;
            }
            site[t] = 1;
            // Sobel gradient of coverage (√2 weights as in Gustavson's edtaa).
            constexpr float r2 = 1.41421356f;
            const float gx = -cov(i - 1, j - 1) - r2 * cov(i - 1, j) - cov(i - 1, j + 1) + cov(i + 1, j - 1) +
                             r2 * cov(i + 1, j) + cov(i + 1, j + 1);
            const float gy = -cov(i - 1, j - 1) - r2 * cov(i, j - 1) - cov(i + 1, j - 1) + cov(i - 1, j + 1) +
                             r2 * cov(i, j + 1) + cov(i + 1, j + 1);
            // Signed distance (texel units) from the site's center to its edge,
            // positive when the center is on the visible side.
            offset[t] = -edge_offset_from_coverage(gx, gy, a);
        }
    feature_transform(n, site, vdt, ws.site_of.data(), ws);  // vdt now holds dist2 to nearest site
    for (int t = 0; t < nn; ++t) {
        const int b = ws.site_of[t];
        if (b < 0) {
            vdt[t] = visible(t) ? kVdtNoBoundaryDistance : -kVdtNoBoundaryDistance;
            continue;
        }
        const float dist = std::sqrt(vdt[t]);
        const float sign = site[t] ? 0.0f : (visible(t) ? 1.0f : -1.0f);
        vdt[t] = (sign * dist + ws.offset[b]) * texel;
    }
}

std::vector<float> compute_vdt(int n, const std::vector<float>& coverage, VdtMode mode) {
    RSL_CHECK_EQ(coverage.size(), size_t(n) * n);
    std::vector<float> vdt(coverage.size());
    VdtWorkspace ws;
    compute_vdt(n, coverage.data(), vdt.data(), mode, ws);
    return vdt;
}


double exact_square_fraction(int n, const float* coverage, const Vec2& center, float half_edge) {
    const double x0 = std::max(-1.0, double(center.x) - half_edge), x1 = std::min(1.0, double(center.x) + half_edge);
    const double y0 = std::max(-1.0, double(center.y) - half_edge), y1 = std::min(1.0, double(center.y) + half_edge);
    if (x1 <= x0 || y1 <= y0) return 1.0;
    const double texel = 2.0 / n;
    const int i0 = std::clamp(int(std::floor((x0 + 1) / texel)), 0, n - 1);
    const int i1 = std::clamp(int(std::floor((x1 + 1) / texel)), 0, n - 1);
    const int j0 = std::clamp(int(std::floor((y0 + 1) / texel)), 0, n - 1);
    const int j1 = std::clamp(int(std::floor((y1 + 1) / texel)), 0, n - 1);
    double sum = 0;
    for (int j = j0; j <= j1; ++j) {
        const double ty0 = -1 + j * texel;
        const double wy = std::min(y1, ty0 + texel) - std::max(y0, ty0);
        if (wy <= 0) continue;
        for (int i = i0; i <= i1; ++i) {
            const double tx0 = -1 + i * texel;
            const double wx = std::min(x1, tx0 + texel) - std::max(x0, tx0);
            if (wx > 0) sum += wx * wy * coverage[j * n + i];
        }
    }
    return sum / ((x1 - x0) * (y1 - y0));
}

}  // namespace rsl
