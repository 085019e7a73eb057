#pragma once
// Between the public API's plain types (include/rsl/rsl.h) and the library's
// (glm vectors, rsl::VertexColors, rsl::Image), for the facade's own files.
#include <cmath>
#include <string>

#include "rsl/rsl.h"
#include "src/core/error.h"
#include "src/core/image.h"
#include "src/core/scene.h"
#include "src/formats/vertex_colors.h"

namespace rsl::api {

inline Vec3 to_vec3(const Float3& v) { return Vec3(v[0], v[1], v[2]); }
inline Float3 to_float3(const Vec3& v) { return {v.x, v.y, v.z}; }

// Every component finite, else rsl::Error naming `what`.
inline Vec3 finite_vec3(const Float3& v, const std::string& what) {
    for (float x : v)
        if (!std::isfinite(x)) throw_error("{}: ({}, {}, {}) is not finite", what, v[0], v[1], v[2]);
    return to_vec3(v);
}

// The pose as the scene's node transform (the quaternion normalized); errors name `what`.
Transform to_transform(const Pose& pose, const std::string& what);
::rsl::Camera to_camera(const Camera& camera);
// The environment turned by `degrees` (+ degrees_per_second · t) about `axis`.
void set_rotation(EnvironmentDesc& environment, const Float3& axis, float degrees, float degrees_per_second);
LocalLight to_local_light(const SphereLight& light);
SphereLight to_sphere_light(const LocalLight& light);

VertexColors to_api(const ::rsl::VertexColors& colors);
// The library's per-part layout back; errors name `what` when the offsets do
// not fit the colours.
::rsl::VertexColors to_internal(const VertexColors& colors, const std::string& what);
Image to_api(const ::rsl::Image& image);
::rsl::Image to_internal(const Image& image, const std::string& what);

// Scene::input_files(): the files it was read from, and the environment
// maps a scene built in code names.
std::vector<std::string> input_files(const ::rsl::Scene& scene);

// A callback that passes at most ~10 calls a second per step (and every end,
// fraction 1) on to `progress`, one call at a time; empty when it is.
Progress throttled(Progress progress);

}  // namespace rsl::api
