#include "src/lightfit/reconstruct.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "src/lightfit/square_fit.h"
#include "src/core/error.h"

namespace rsl::lightfit {

namespace {

struct PlacedLight {
    Frame frame;
    float half_edge;      // in the fit chart
    float cos_reach;      // texels with dot(d, c) below this cannot touch the square
    Color radiance;
};

std::vector<PlacedLight> place(const RslSet& set, int n) {
    const float texel_reach = 2.0f * 2.0f / n;  // a texel's diagonal in the chart, generously
    std::vector<PlacedLight> placed;
    for (const auto& light : set.lights) {
        PlacedLight p;
        p.frame = Frame::from_normal_tangent(light.center, Vec3(0, 1, 0));
        p.half_edge = light.half_diagonal / std::numbers::sqrt2_v<float>;
        // Chart radius ρ is the chord 2 sin(α/2) of the angle α from the center.
        const float rho = std::min(light.half_diagonal + texel_reach, 2.0f);
        p.cos_reach = rho >= 2.0f ? -2.0f : std::cos(2.0f * std::asin(0.5f * rho));
        p.radiance = light.radiance;
        placed.push_back(p);
    }
    return placed;
}

float covered_fraction(const PlacedLight& light, const Vec3& direction, SquareTurns turns) {
    const Vec2 q = fit_chart(light.frame, direction);
    if (turns == SquareTurns::kAligned)
        return std::abs(q.x) <= light.half_edge && std::abs(q.y) <= light.half_edge ? 1.0f : 0.0f;
    int inside = 0;
    for (float theta : kFitTurns) {
        const float c = std::cos(theta), s = std::sin(theta);
        const float u = q.x * c + q.y * s, v = -q.x * s + q.y * c;
        inside += std::abs(u) <= light.half_edge && std::abs(v) <= light.half_edge;
    }
    return float(inside) / kFitTurns.size();
}

}  // namespace

CubeMap reconstruct(const RslSet& set, int n, SquareTurns turns, int supersampling) {
    RSL_CHECK_GT(n, 0);
    RSL_CHECK_GT(supersampling, 0);
    CubeMap out(n);
    const auto lights = place(set, n);
    const int ss = supersampling;
    tbb::parallel_for(0, out.texel_count(), [&](int k) {
        const CubeTexel t = out.texel(k);
        const Vec3 center = out.texel_direction(k);
        Color sum(0);
        for (const auto& light : lights) {
            if (glm::dot(center, light.frame.z) < light.cos_reach) continue;
            float covered = 0, total = 0;
            for (int b = 0; b < ss; ++b)
                for (int a = 0; a < ss; ++a) {
                    const float s = -1.0f + 2.0f * (t.i + (a + 0.5f) / ss) / n;
                    const float u = -1.0f + 2.0f * (t.j + (b + 0.5f) / ss) / n;
                    // dω/ds dt on a unit cube face.
                    const float w = 1.0f / std::pow(1.0f + s * s + u * u, 1.5f);
                    covered += w * covered_fraction(light, glm::normalize(CubeMap::face_direction(t.face, s, u)), turns);
                    total += w;
                }
            sum += light.radiance * (covered / total);
        }
        out.radiance(k) = sum;
    });
    return out;
}

double relative_l2_error(const CubeMap& reference, const CubeMap& approximation) {
    RSL_CHECK_EQ(reference.resolution(), approximation.resolution());
    double diff = 0, norm = 0;
    for (int k = 0; k < reference.texel_count(); ++k) {
        const DVec3 a(reference.radiance(k)), b(approximation.radiance(k));
        diff += glm::dot(a - b, a - b) * reference.solid_angle(k);
        norm += glm::dot(a, a) * reference.solid_angle(k);
    }
    return norm > 0 ? std::sqrt(diff / norm) : std::sqrt(diff);
}

Image fit_preview(const CubeMap& map, const RslSet& set, int panel_width) {
    RSL_CHECK_EQ(set.region_of_texel.size(), size_t(map.texel_count()));
    const int w = panel_width, h = panel_width / 2;
    const Image original = cube_to_latlong(map, w);
    // Twice the source resolution keeps the squares' edges crisp in the panel.
    const Image fitted = cube_to_latlong(reconstruct(set, 2 * map.resolution(), SquareTurns::kAligned), w);
    RSL_CHECK_EQ(original.height, h);

    std::vector<float> lum;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) lum.push_back(luminance(original.rgb(x, y)));
    auto p99 = lum.begin() + std::ptrdiff_t(0.99 * (lum.size() - 1));
    std::nth_element(lum.begin(), p99, lum.end());
    const float scale = *p99 > 0 ? 0.9f / *p99 : 1.0f;

    std::vector<int> label(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            label[size_t(y) * w + x] =
                set.region_of_texel[map.index_of(latlong_direction((x + 0.5f) / w, (y + 0.5f) / h))];

    Image preview(3 * w, h);
    const Color green(0.1f, 1.0f, 0.1f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Color c = original.rgb(x, y) * scale;
            const int here = label[size_t(y) * w + x];
            const bool boundary = here != label[size_t(y) * w + (x + 1) % w] ||
                                  (y + 1 < h && here != label[size_t(y + 1) * w + x]);
            preview.set_rgb(x, y, c);
            preview.set_rgb(w + x, y, boundary ? green : c);
            preview.set_rgb(2 * w + x, y, fitted.rgb(x, y) * scale);
        }
    return preview;
}

}  // namespace rsl::lightfit
