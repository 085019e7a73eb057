#pragma once
// Vector types and the orthonormal frames used everywhere (see docs/design/CONVENTIONS.md).
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "src/shading/frames.h"

namespace rsl {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;
using Quat = glm::quat;
using DVec3 = glm::dvec3;
using Color = glm::vec3;  // linear RGB radiance or reflectance

// Before a loop over arrays reached through pointers whose iterations touch
// disjoint memory the compiler cannot prove so: vectorize it without the
// run-time alias checks (too many of them, and GCC gives up instead).
#if defined(__clang__)
#define RSL_VECTORIZE_NO_ALIAS _Pragma("clang loop vectorize(assume_safety)")
#else
#define RSL_VECTORIZE_NO_ALIAS _Pragma("GCC ivdep")
#endif

inline constexpr float kPi = shading::kPi;
inline constexpr float kSqrt2 = shading::kSqrt2;
inline constexpr float kInvPi = std::numbers::inv_pi_v<float>;

inline float luminance(const Color& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Any unit vector orthogonal to n (the shading core's, shared with the GPU).
using shading::any_orthonormal;

// Local frame at a vertex: z = shading normal n, x = tangent t orthogonalized
// against n, y = n × t. Visibility tables (SVDF) live in this frame.
struct Frame {
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};

    Frame() = default;
    Frame(const Vec3& x_, const Vec3& y_, const Vec3& z_) : x(x_), y(y_), z(z_) {}

    // Gram-Schmidt: keeps n exactly, falls back to any orthonormal tangent when
    // t is (nearly) parallel to n or missing.
    static Frame from_normal_tangent(const Vec3& n, const Vec3& t) {
        const shading::LocalFrame f = shading::frame_from_normal_tangent(n, t);
        return Frame(f.x, f.y, f.z);
    }
    static Frame from_normal(const Vec3& n) { return from_normal_tangent(n, Vec3(0)); }

    Vec3 to_local(const Vec3& v) const { return Vec3(glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)); }
    Vec3 to_world(const Vec3& v) const { return x * v.x + y * v.y + z * v.z; }
};

}  // namespace rsl
