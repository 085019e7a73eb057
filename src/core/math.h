#pragma once
// Vector types and the orthonormal frames used everywhere (see docs/CONVENTIONS.md).
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace rsl {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;
using Quat = glm::quat;
using DVec3 = glm::dvec3;
using Color = glm::vec3;  // linear RGB radiance or reflectance

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = std::numbers::inv_pi_v<float>;

inline float luminance(const Color& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Any unit vector orthogonal to n (Duff et al. 2017, branchless ONB).
inline Vec3 any_orthonormal(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

// Local frame at a vertex: z = shading normal n, x = tangent t orthogonalized
// against n, y = n × t. Visibility tables (SVDF) live in this frame.
struct Frame {
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};

    Frame() = default;
    Frame(const Vec3& x_, const Vec3& y_, const Vec3& z_) : x(x_), y(y_), z(z_) {}

    // Gram-Schmidt: keeps n exactly, falls back to any orthonormal tangent when
    // t is (nearly) parallel to n or missing.
    static Frame from_normal_tangent(const Vec3& n, const Vec3& t) {
        Vec3 z = glm::normalize(n);
        Vec3 x = t - z * glm::dot(z, t);
        const float len2 = glm::dot(x, x);
        x = len2 > 1e-12f ? x / std::sqrt(len2) : any_orthonormal(z);
        return Frame(x, glm::cross(z, x), z);
    }
    static Frame from_normal(const Vec3& n) { return from_normal_tangent(n, Vec3(0)); }

    Vec3 to_local(const Vec3& v) const { return Vec3(glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)); }
    Vec3 to_world(const Vec3& v) const { return x * v.x + y * v.y + z * v.z; }
};

}  // namespace rsl
