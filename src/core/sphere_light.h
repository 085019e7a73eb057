#pragma once
// What a scene's sphere light emits. Here, not in the ground truth, because
// every renderer must define the light exactly as the reference does.
#include <algorithm>
#include <cmath>

#include "src/core/scene.h"
#include "src/shading/squares.h"

namespace rsl {

// Radiance of a uniform spherical emitter of radius a and RGB power Φ:
// Φ = L · π · 4πa²  ⇒  L = Φ / (4π² a²).
inline Color sphere_light_radiance(const LocalLight& light) {
    return light.power / (4.0f * kPi * kPi * light.radius * light.radius);
}

// The (scale, offset) of shading::spot_cone_factor for a light: glTF's
// lightAngleScale and lightAngleOffset; (0, 1), no falloff, for a point light.
inline Vec2 spot_cone_scale_offset(const LocalLight& light) {
    if (!light.spot) return Vec2(0, 1);
    const float cos_outer = std::cos(light.outer_cone_radians);
    const float scale = 1.0f / std::max(1e-3f, std::cos(light.inner_cone_radians) - cos_outer);
    return Vec2(scale, -cos_outer * scale);
}

// The share of a light's radiance that reaches point x (its cone's factor).
inline float spot_cone_factor_at(const Vec3& x, const Vec3& center, const Vec3& axis, const Vec2& scale_offset) {
    const Vec3 d = x - center;
    const float len = glm::length(d);
    if (!(len > 0)) return 1.0f;
    return shading::spot_cone_factor(axis, d / len, scale_offset.x, scale_offset.y);
}

}  // namespace rsl
