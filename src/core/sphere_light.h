#pragma once
// What a scene's sphere light emits. Here, not in the ground truth, because
// every renderer must define the light exactly as the reference does.
#include "src/core/scene.h"

namespace rsl {

// Radiance of a uniform spherical emitter of radius a and RGB power Φ:
// Φ = L · π · 4πa²  ⇒  L = Φ / (4π² a²).
inline Color sphere_light_radiance(const LocalLight& light) {
    return light.power / (4.0f * kPi * kPi * light.radius * light.radius);
}

}  // namespace rsl
