#include "src/lightfit/fit_limits.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>

namespace rsl {

namespace {

double degrees_of(double solid_angle) { return std::sqrt(solid_angle) * 180.0 / kPi; }

}  // namespace

PointLikeSource find_point_like_source(const CubeMap& map) {
    PointLikeSource out;
    double total = 0;
    int brightest = -1;
    for (int i = 0; i < map.texel_count(); ++i) {
        total += double(luminance(map.radiance(i))) * map.solid_angle(i);
        if (brightest < 0 || luminance(map.radiance(i)) > luminance(map.radiance(brightest))) brightest = i;
    }
    if (brightest < 0 || !(total > 0)) return out;
    // The texels above a tenth of the peak joined to the brightest: a source
    // smaller than a texel lights one, or up to 2×2 where it straddles their edges.
    const float threshold = 0.1f * luminance(map.radiance(brightest));
    std::vector<int> cluster{brightest};
    for (size_t next = 0; next < cluster.size() && cluster.size() <= kPointLikeTexels; ++next)
        for (const int neighbor : map.neighbors(cluster[next]))
            if (luminance(map.radiance(neighbor)) >= threshold &&
                std::find(cluster.begin(), cluster.end(), neighbor) == cluster.end())
                cluster.push_back(neighbor);
    if (cluster.size() > kPointLikeTexels) return out;
    double energy = 0, area = 0;
    for (const int texel : cluster)
        energy += double(luminance(map.radiance(texel))) * map.solid_angle(texel), area += map.solid_angle(texel);
    if (energy < kPointLikeShare * total) return out;
    out.found = true;
    out.texel = brightest;
    out.share = energy / total;
    out.texel_degrees = degrees_of(area / double(cluster.size()));
    return out;
}

CrowdedLight find_crowded_light(const CubeMap& map, const RslSet& set) {
    CrowdedLight out;
    if (set.region_of_texel.size() != size_t(map.texel_count()) || set.lights.empty()) return out;
    const size_t k = set.lights.size();
    auto region_of = [&](int texel) {
        const int l = set.region_of_texel[size_t(texel)];
        return l >= 0 && size_t(l) < k ? l : -1;
    };
    auto energy_of = [&](int texel) { return double(luminance(map.radiance(texel))) * map.solid_angle(texel); };
    std::vector<double> energy(k, 0.0), peak(k, 0.0), outside(k, 0.0);
    double total = 0;
    for (int i = 0; i < map.texel_count(); ++i) {
        total += energy_of(i);
        const int l = region_of(i);
        if (l < 0) continue;
        energy[size_t(l)] += energy_of(i);
        peak[size_t(l)] = std::max(peak[size_t(l)], double(luminance(map.radiance(i))));
        // Outside the square's circumscribed cone (2·asin(r/2) about its centre, in the equal-area
        // chart: src/lightfit/square_light.h), widened by the texel's own half-width.
        const RotatableSquareLight& light = set.lights[size_t(l)];
        const double cone = 2.0 * std::asin(std::min(0.5 * double(light.half_diagonal), 1.0)) +
                            0.5 * std::sqrt(double(map.solid_angle(i)));
        const double angle = std::acos(std::clamp(double(glm::dot(map.texel_direction(i), light.center)), -1.0, 1.0));
        if (angle > cone) outside[size_t(l)] += energy_of(i);
    }
    if (!(total > 0)) return out;
    // Per region, the texels above a tenth of its peak radiance: their light and their solid angle.
    std::vector<double> bright_energy(k, 0.0), bright_area(k, 0.0);
    for (int i = 0; i < map.texel_count(); ++i) {
        const int l = region_of(i);
        if (l < 0 || !(double(luminance(map.radiance(i))) >= 0.1 * peak[size_t(l)])) continue;
        bright_energy[size_t(l)] += energy_of(i);
        bright_area[size_t(l)] += map.solid_angle(i);
    }
    for (size_t l = 0; l < k; ++l) {
        const double square = set.lights[l].solid_angle();
        const bool too_soft = energy[l] >= kCrowdedShare * total && bright_energy[l] >= kCrowdedConcentration * energy[l] &&
                              square >= kCrowdedSpread * bright_area[l];
        const bool too_hard = outside[l] >= kMisplacedShare * total;
        if (!too_soft && !too_hard) continue;
        const double share = (too_hard ? outside[l] : energy[l]) / total;
        if (out.found && share <= out.share) continue;
        out.found = true;
        out.too_hard = too_hard;
        out.light = int(l);
        out.share = share;
        out.light_degrees = degrees_of(square);
        out.source_degrees = degrees_of(bright_area[l]);
    }
    return out;
}

std::string point_like_note(const std::string& name, const CubeMap& map, const PointLikeSource& source) {
    if (!source.found) return "";
    return fmt::format("{}: a source within 2×2 texels of the 6×{}² cube map gives {:.0f}% of its light; whatever "
                       "its true size, its shadows are those of a light a texel or two wide ({:.1f}° texels; "
                       "environment.resolution {} for {:.1f}°)",
                       name, map.resolution(), 100.0 * source.share, source.texel_degrees, 4 * map.resolution(),
                       source.texel_degrees / 4.0);
}

std::string crowded_light_warning(const std::string& name, int lights, const CrowdedLight& crowded) {
    if (!crowded.found) return "";
    const std::string what =
        crowded.too_hard
            ? fmt::format("light {} is a {:.1f}° square drawn to a {:.1f}° bright region, and {:.0f}% of the map's "
                          "light around it falls outside the square, so its shadows come out too hard",
                          crowded.light, crowded.light_degrees, crowded.source_degrees, 100.0 * crowded.share)
            : fmt::format("light {} ({:.0f}% of the light) is a {:.1f}° square around a {:.1f}° bright source, so "
                          "its shadows come out as soft as the square",
                          crowded.light, 100.0 * crowded.share, crowded.light_degrees, crowded.source_degrees);
    return fmt::format("{}: {} lights are too few for this map: {}; more lights (--lights, RenderSettings::lights) "
                       "give the source a square of its own",
                       name, lights, what);
}

}  // namespace rsl
