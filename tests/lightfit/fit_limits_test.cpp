// The limits a fit reports (src/lightfit/fit_limits.h), on maps whose answer
// is known by construction: a sky with one bright texel, a 2×2 spot, a 3×3
// patch, and the lights fitted to them.
#include <cmath>

#include <catch2/catch.hpp>

#include "src/lightfit/fit_limits.h"
#include "src/lightfit/scene_lights.h"

namespace rsl {
namespace {

// A uniform sky of radiance 1 with `bright` texels of radiance `level`, the
// first at (face 4, i, j) and the others to its right and below (side × side).
CubeMap sky_with_spot(int n, int i, int j, int side, float level) {
    CubeMap map(n);
    for (Color& c : map.radiances()) c = Color(1.0f);
    for (int dj = 0; dj < side; ++dj)
        for (int di = 0; di < side; ++di) map.radiances()[size_t(map.index(4, i + di, j + dj))] = Color(level);
    return map;
}

double share_of(const CubeMap& map, int i, int j, int side) {
    double spot = 0, total = 0;
    for (int t = 0; t < map.texel_count(); ++t) total += double(luminance(map.radiance(t))) * map.solid_angle(t);
    for (int dj = 0; dj < side; ++dj)
        for (int di = 0; di < side; ++di) {
            const int t = map.index(4, i + di, j + dj);
            spot += double(luminance(map.radiance(t))) * map.solid_angle(t);
        }
    return spot / total;
}

TEST_CASE("a source within 2×2 texels is point-like; a wider one or a faint one is not", "[lightfit][limits]") {
    for (int side : {1, 2}) {
        const CubeMap map = sky_with_spot(16, 7, 9, side, 5e3f);
        const PointLikeSource source = find_point_like_source(map);
        INFO("side " << side);
        REQUIRE(source.found);
        CHECK(source.texel == map.index(4, 7, 9));
        CHECK(source.share == Approx(share_of(map, 7, 9, side)).epsilon(1e-6));
        if (side == 1)  // √Ω of the texel, in degrees
            CHECK(source.texel_degrees == Approx(std::sqrt(map.solid_angle(source.texel)) * 180.0 / kPi));
        CHECK(point_like_note("sky.exr", map, source).find("sky.exr: a source within 2×2 texels") == 0);
    }
    // 3×3 texels are a source the map resolves.
    CHECK(!find_point_like_source(sky_with_spot(16, 7, 9, 3, 5e3f)).found);
    // A single texel with under a tenth of the light: too little to matter.
    const CubeMap faint = sky_with_spot(16, 7, 9, 1, 40.0f);
    REQUIRE(share_of(faint, 7, 9, 1) < kPointLikeShare);
    CHECK(!find_point_like_source(faint).found);
    CHECK(point_like_note("sky.exr", faint, find_point_like_source(faint)).empty());
}

TEST_CASE("one light over a sky and its sun is crowded; with a light of its own the sun is not", "[lightfit][limits]") {
    // One light: the fit draws the square to the sun, and the sky's light
    // (1 × 4π against the sun's 5,000 × one texel) goes with it.
    const CubeMap map = sky_with_spot(16, 7, 9, 1, 5e3f);
    const RslSet one = fit_environment_lights(map, 1, true);
    REQUIRE(one.lights.size() == 1);
    const CrowdedLight crowded = find_crowded_light(map, one);
    REQUIRE(crowded.found);
    CHECK(crowded.too_hard);
    CHECK(crowded.light == 0);
    CHECK(crowded.share > 0.9 * (1.0 - share_of(map, 7, 9, 1)));  // nearly all the sky is outside the square
    CHECK(crowded.share < 1.0 - share_of(map, 7, 9, 1));
    CHECK(crowded_light_warning("sky.exr", 1, crowded).find("sky.exr: 1 lights are too few") == 0);
    // A square set by hand over a quarter of the sphere around the sun: too soft.
    RslSet wide = one;
    wide.lights[0].half_diagonal = std::sqrt(0.5f * kPi);  // 2r² = π
    const CrowdedLight soft = find_crowded_light(map, wide);
    REQUIRE(soft.found);
    CHECK(!soft.too_hard);
    CHECK(soft.share == Approx(1.0));
    CHECK(soft.light_degrees > 10 * soft.source_degrees);
    for (int k : {2, 8, 30}) {
        const RslSet set = fit_environment_lights(map, k, true);
        INFO(k << " lights");
        CHECK(!find_crowded_light(map, set).found);
    }
    // Without region labels (a rotated or loaded set) nothing is claimed.
    RslSet rotated = one;
    rotated.rotate(Mat3(1.0f));
    CHECK(!find_crowded_light(map, rotated).found);
}

}  // namespace
}  // namespace rsl
