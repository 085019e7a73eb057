#pragma once
// The project's own environment maps, as float RGB lat-long images in the
// convention of src/core/envmap.h (every pixel's direction comes from
// latlong_direction at the pixel centre):
//  - sunsky:   sky gradient over a darker ground and a 0.5°-radius sun that
//              carries 75% of the map's energy (the all-frequency case);
//  - studio:   dark room with three rectangular softboxes of different sizes
//              and colours (key, fill, rim);
//  - overcast: the CIE standard overcast sky, L(θ) = L_z (1 + 2 cos θ) / 3,
//              over ground lit by it (low frequency).
#include <array>

#include "src/core/image.h"
#include "src/core/math.h"

namespace rsl::assets {

inline constexpr int kEnvironmentWidth = 512, kEnvironmentHeight = 256;

struct SunSky {
    Vec3 sun_direction = glm::normalize(Vec3(-0.52f, 0.57f, 0.63f));  // 35° up, from the front left (+Z, −X)
    float sun_radius_degrees = 0.5f;
    float sun_energy_fraction = 0.75f;  // of ∫ L dω over the sphere, per channel (luminance)
};
Image make_sunsky(const SunSky& params = {}, int width = kEnvironmentWidth, int height = kEnvironmentHeight);

// A rectangular softbox: the directions whose gnomonic projection onto the
// plane facing `center` falls within ±tan(half_width) × ±tan(half_height).
struct Softbox {
    Vec3 center;  // unit direction
    float half_width_degrees, half_height_degrees;
    Color radiance;
    bool contains(const Vec3& dir) const;
};
std::array<Softbox, 3> studio_softboxes();
Image make_studio(int width = kEnvironmentWidth, int height = kEnvironmentHeight);

Image make_overcast(int width = kEnvironmentWidth, int height = kEnvironmentHeight);

}  // namespace rsl::assets
