#pragma once
// Random test cases that are the same under every compiler: the components
// are drawn one statement at a time, because the order in which a call's
// arguments are evaluated, as in Vec3(u(rng), u(rng), u(rng)), differs
// between GCC and Clang, and the CI's sanitizer build uses Clang.
#include <random>

#include "src/core/math.h"

namespace rsl::test {

// A glm vector whose components are drawn in order x, y, z, w.
template <typename Vector, typename Distribution, typename Rng>
Vector random_vector(Distribution& distribution, Rng& rng) {
    Vector v;
    for (int i = 0; i < Vector::length(); ++i) v[i] = typename Vector::value_type(distribution(rng));
    return v;
}

template <typename Distribution, typename Rng>
Vec2 random_vec2(Distribution& distribution, Rng& rng) {
    return random_vector<Vec2>(distribution, rng);
}

template <typename Distribution, typename Rng>
Vec3 random_vec3(Distribution& distribution, Rng& rng) {
    return random_vector<Vec3>(distribution, rng);
}

template <typename Distribution, typename Rng>
Vec4 random_vec4(Distribution& distribution, Rng& rng) {
    return random_vector<Vec4>(distribution, rng);
}

template <typename Distribution, typename Rng>
DVec3 random_dvec3(Distribution& distribution, Rng& rng) {
    return random_vector<DVec3>(distribution, rng);
}

// Quat(w, x, y, z), drawn in that order; not normalized.
template <typename Distribution, typename Rng>
Quat random_quat(Distribution& distribution, Rng& rng) {
    const Vec4 v = random_vec4(distribution, rng);
    return Quat(v.x, v.y, v.z, v.w);
}

// glm::dquat(w, x, y, z), drawn in that order; not normalized.
template <typename Distribution, typename Rng>
glm::dquat random_dquat(Distribution& distribution, Rng& rng) {
    const glm::dvec4 v = random_vector<glm::dvec4>(distribution, rng);
    return glm::dquat(v.x, v.y, v.z, v.w);
}

// A direction uniform on the unit sphere (normalized Gaussian).
template <typename Rng>
Vec3 random_unit_vector(Rng& rng) {
    std::normal_distribution<float> normal;
    return glm::normalize(random_vec3(normal, rng));
}

}  // namespace rsl::test
