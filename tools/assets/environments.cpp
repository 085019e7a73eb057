#include "tools/assets/environments.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "src/core/envmap.h"
#include "src/core/error.h"

namespace rsl::assets {
namespace {

float radians(float degrees) { return degrees * kPi / 180.0f; }

float smoothstep(float edge0, float edge1, float x) {
    const float s = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return s * s * (3 - 2 * s);
}

// Direction through a point of pixel (x, y) given by sub-pixel offsets in [0, 1).
Vec3 pixel_direction(const Image& image, int x, int y, float dx = 0.5f, float dy = 0.5f) {
    return latlong_direction((x + dx) / image.width, (y + dy) / image.height);
}

// Solid angle of one pixel of row y: Δφ · (cos θ_top − cos θ_bottom), with cos θ
// read from the convention's own direction of the row edges.
double pixel_solid_angle(const Image& image, int y) {
    const double cos_top = latlong_direction(0, float(y) / image.height).y;
    const double cos_bottom = latlong_direction(0, float(y + 1) / image.height).y;
    return 2 * std::numbers::pi / image.width * (cos_top - cos_bottom);
}

// Fraction of pixel (x, y) covered by a predicate on directions, from an n × n grid of samples.
template <typename Inside>
float coverage(const Image& image, int x, int y, int n, const Inside& inside) {
    int hits = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) hits += inside(pixel_direction(image, x, y, (i + 0.5f) / n, (j + 0.5f) / n));
    return float(hits) / float(n * n);
}

template <typename Shade>
Image shade_latlong(int width, int height, const Shade& shade) {
    RSL_CHECK(width > 0 && height > 0);
    Image image(width, height, 3);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) image.set_rgb(x, y, shade(image, x, y));
    });
    return image;
}

}  // namespace

// ---------------------------------------------------------------- sun and sky

Image make_sunsky(const SunSky& params, int width, int height) {
    const Vec3 sun = glm::normalize(params.sun_direction);
    const Color zenith(0.16f, 0.32f, 0.85f), horizon(0.75f, 0.85f, 1.0f), ground(0.22f, 0.19f, 0.15f);
    const Color sun_tint(1.0f, 0.93f, 0.82f);
    // Sky and ground, blended over ±1.5° at the horizon, plus a faint
    // circumsolar aureole (a few degrees wide): all smooth at pixel scale.
    Image image = shade_latlong(width, height, [&](const Image& img, int x, int y) {
        const Vec3 d = pixel_direction(img, x, y);
        const float elevation = std::asin(std::clamp(d.y, -1.0f, 1.0f));
        const Color sky = glm::mix(horizon, zenith, std::sqrt(std::max(0.0f, d.y)));
        const float angle_to_sun = std::acos(std::clamp(glm::dot(d, sun), -1.0f, 1.0f));
        const Color aureole = sun_tint * (1.5f * std::exp(-angle_to_sun / radians(4.0f)));
        return glm::mix(ground, sky + aureole, smoothstep(radians(-1.5f), radians(1.5f), elevation));
    });

    // The sun disc: anti-aliased coverage near it, then one radiance chosen so
    // that the disc's energy is exactly the requested share of the total.
    const float cos_radius = std::cos(radians(params.sun_radius_degrees));
    const float near = radians(params.sun_radius_degrees) + 2 * kPi / width * 2;  // disc + ~2 pixels
    const auto in_sun = [&](const Vec3& d) { return glm::dot(d, sun) >= cos_radius; };
    std::vector<float> cover(size_t(width) * height, 0.0f);
    double covered_solid_angle = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (std::acos(std::clamp(glm::dot(pixel_direction(image, x, y), sun), -1.0f, 1.0f)) > near) continue;
            const float c = coverage(image, x, y, 32, in_sun);
            cover[size_t(y) * width + x] = c;
            covered_solid_angle += c * pixel_solid_angle(image, y);
        }
    RSL_CHECK_GT(covered_solid_angle, 0.0);
    const double sky_energy = luminance(Color(latlong_energy(image)));
    const double f = params.sun_energy_fraction;
    const double sun_luminance = f / (1 - f) * sky_energy / covered_solid_angle;
    const Color sun_radiance = sun_tint * float(sun_luminance / luminance(sun_tint));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (const float c = cover[size_t(y) * width + x]; c > 0) image.set_rgb(x, y, image.rgb(x, y) + c * sun_radiance);
    return image;
}

// ---------------------------------------------------------------- studio

bool Softbox::contains(const Vec3& dir) const {
    const Vec3 right = glm::normalize(glm::cross(Vec3(0, 1, 0), center));
    const Vec3 up = glm::cross(center, right);
    const float depth = glm::dot(dir, center);
    if (depth <= 0) return false;
    return std::abs(glm::dot(dir, right)) <= depth * std::tan(radians(half_width_degrees)) &&
           std::abs(glm::dot(dir, up)) <= depth * std::tan(radians(half_height_degrees));
}

namespace {
// Direction at `elevation` above the horizon and `azimuth` from +Z towards +X (degrees).
Vec3 direction(float elevation, float azimuth) {
    const float e = radians(elevation), a = radians(azimuth);
    return Vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
}
}  // namespace

std::array<Softbox, 3> studio_softboxes() {
    return {{
        {direction(40, -45), 22, 15, Color(6.0f, 5.5f, 4.8f)},     // key: large, warm, front left
        {direction(15, 70), 9, 18, Color(1.1f, 1.4f, 2.0f)},       // fill: tall strip, cool, right
        {direction(55, 170), 6, 4, Color(24.0f, 24.0f, 24.0f)},    // rim: small and bright, behind
    }};
}

Image make_studio(int width, int height) {
    const auto boxes = studio_softboxes();
    return shade_latlong(width, height, [&](const Image& img, int x, int y) {
        const Vec3 d = pixel_direction(img, x, y);
        // Dim walls, a darker floor.
        Color L = glm::mix(Color(0.012f), Color(0.035f, 0.034f, 0.032f), smoothstep(-0.2f, 0.3f, d.y));
        for (const Softbox& box : boxes) {
            const float c = coverage(img, x, y, 4, [&](const Vec3& s) { return box.contains(s); });
            L += c * box.radiance;
        }
        return L;
    });
}

// ---------------------------------------------------------------- overcast

Image make_overcast(int width, int height) {
    const Color zenith(0.95f, 0.97f, 1.0f);  // L_z, slightly cool
    const float ground_albedo = 0.3f;
    // Ground radiance = ρ E / π with the overcast sky's horizontal irradiance E = (7/9) π L_z.
    const Color ground = zenith * (ground_albedo * 7.0f / 9.0f) * Color(1.0f, 0.95f, 0.88f);
    return shade_latlong(width, height, [&](const Image& img, int x, int y) {
        const Vec3 d = pixel_direction(img, x, y);
        const Color sky = zenith * ((1 + 2 * std::max(0.0f, d.y)) / 3);
        // The step between horizon sky (L_z / 3) and ground is spread over 10°.
        return glm::mix(ground, sky, smoothstep(-std::sin(radians(10.0f)), 0.0f, d.y));
    });
}

}  // namespace rsl::assets
