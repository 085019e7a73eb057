#pragma once
// Random test cases that are the same under every compiler: the components
// are drawn one statement at a time, because the order in which a call's
// arguments are evaluated (test::random_vec3(u, rng)) differs between
// GCC and Clang, and the CI's sanitizer build uses Clang.
#include <random>

#include "src/core/math.h"
#include "tests/random_cases.h"

namespace rsl::test {

template <typename Distribution, typename Rng>
Vec2 random_vec2(Distribution& distribution, Rng& rng) {
    const float x = distribution(rng);
    const float y = distribution(rng);
    return Vec2(x, y);
}

template <typename Distribution, typename Rng>
Vec3 random_vec3(Distribution& distribution, Rng& rng) {
    const float x = distribution(rng);
    const float y = distribution(rng);
    const float z = distribution(rng);
    return Vec3(x, y, z);
}

template <typename Distribution, typename Rng>
Vec4 random_vec4(Distribution& distribution, Rng& rng) {
    const Vec3 xyz = random_vec3(distribution, rng);
    const float w = distribution(rng);
    return Vec4(xyz, w);
}

// Quat(w, x, y, z), drawn in that order; not normalized.
template <typename Distribution, typename Rng>
Quat random_quat(Distribution& distribution, Rng& rng) {
    const Vec4 v = random_vec4(distribution, rng);
    return Quat(v.x, v.y, v.z, v.w);
}

// The same in double precision.
template <typename Distribution, typename Rng>
DVec3 random_dvec3(Distribution& distribution, Rng& rng) {
    const double x = distribution(rng);
    const double y = distribution(rng);
    const double z = distribution(rng);
    return DVec3(x, y, z);
}

// glm::dquat(w, x, y, z), drawn in that order; not normalized.
template <typename Distribution, typename Rng>
glm::dquat random_dquat(Distribution& distribution, Rng& rng) {
    const DVec3 wxy = random_dvec3(distribution, rng);
    const double z = distribution(rng);
    return glm::dquat(wxy.x, wxy.y, wxy.z, z);
}

// A direction uniform on the unit sphere (normalized Gaussian).
template <typename Rng>
Vec3 random_unit_vector(Rng& rng) {
    std::normal_distribution<float> normal;
    return glm::normalize(random_vec3(normal, rng));
}

}  // namespace rsl::test
