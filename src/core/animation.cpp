// Keyframe tracks (glTF semantics), rigid transforms and the scene's node
// hierarchy evaluated at a time.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.h"
#include "src/core/scene.h"

namespace rsl {

namespace {

// Where t falls among the keys: segment [k, k+1] and the fraction s in it.
// Times outside the track clamp to its ends.
struct KeySegment {
    size_t k = 0;
    float s = 0;
    float duration = 0;  // t_{k+1} − t_k
    bool at_end = false;  // t at or past the last key (or a single key)
};

KeySegment find_segment(const std::vector<float>& times, float t) {
    RSL_CHECK(!times.empty());
    KeySegment seg;
    if (times.size() == 1 || t >= times.back()) {
        seg.k = times.size() - 1;
        seg.at_end = true;
        return seg;
    }
    if (t <= times.front()) return seg;
    // First key strictly after t; the segment starts one before it.
    seg.k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    seg.duration = times[seg.k + 1] - times[seg.k];
    seg.s = seg.duration > 0 ? (t - times[seg.k]) / seg.duration : 0.0f;
    return seg;
}

// glTF CUBICSPLINE stores (in-tangent, value, out-tangent) per key.
template <typename T>
T hermite(const std::vector<T>& triplets, const KeySegment& seg) {
    const float s = seg.s, s2 = s * s, s3 = s2 * s;
    const T& v0 = triplets[3 * seg.k + 1];
    const T& out0 = triplets[3 * seg.k + 2];
    const T& in1 = triplets[3 * (seg.k + 1)];
    const T& v1 = triplets[3 * (seg.k + 1) + 1];
    return (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * seg.duration * out0 + (-2 * s3 + 3 * s2) * v1 +
           (s3 - s2) * seg.duration * in1;
}

size_t expected_value_count(Interpolation interpolation, size_t keys) {
    return interpolation == Interpolation::CubicSpline ? 3 * keys : keys;
}

// Spherical interpolation along the shorter arc (q and −q are the same rotation).
Quat slerp_shortest(Quat a, Quat b, float s) {
    float cosine = glm::dot(a, b);
    if (cosine < 0) {
        b = -b;
        cosine = -cosine;
    }
    if (cosine > 0.9995f) return glm::normalize(a * (1 - s) + b * s);  // nearly equal: lerp is exact enough
    const float angle = std::acos(cosine);
    const float sine = std::sin(angle);
    return glm::normalize(a * (std::sin((1 - s) * angle) / sine) + b * (std::sin(s * angle) / sine));
}

}  // namespace

Vec3 Vec3Track::sample(float t) const {
    RSL_CHECK_EQ(values.size(), expected_value_count(interpolation, times.size()));
    const KeySegment seg = find_segment(times, t);
    const bool cubic = interpolation == Interpolation::CubicSpline;
    auto value = [&](size_t k) { return cubic ? values[3 * k + 1] : values[k]; };
    if (seg.at_end || interpolation == Interpolation::Step || seg.s == 0) return value(seg.k);
    if (cubic) return hermite(values, seg);
    return glm::mix(value(seg.k), value(seg.k + 1), seg.s);
}

Quat QuatTrack::sample(float t) const {
    RSL_CHECK_EQ(values.size(), expected_value_count(interpolation, times.size()));
    const KeySegment seg = find_segment(times, t);
    const bool cubic = interpolation == Interpolation::CubicSpline;
    auto value = [&](size_t k) { return cubic ? values[3 * k + 1] : values[k]; };
    if (seg.at_end || interpolation == Interpolation::Step || seg.s == 0) return glm::normalize(value(seg.k));
    if (cubic) return glm::normalize(hermite(values, seg));
    return slerp_shortest(glm::normalize(value(seg.k)), glm::normalize(value(seg.k + 1)), seg.s);
}

Mat4 Transform::matrix() const {
    // glTF order: M = T · R · S.
    Mat4 m = glm::mat4_cast(glm::normalize(rotation));
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = Vec4(translation, 1.0f);
    return m;
}

Transform SceneNode::local_at(float t) const {
    Transform local = rest;
    if (translation) local.translation = translation->sample(t);
    if (rotation) local.rotation = rotation->sample(t);
    if (scale) local.scale = scale->sample(t);
    return local;
}

Mat3 EnvironmentDesc::rotation_at(float t) const {
    const float degrees = rotation_degrees + rotation_degrees_per_second * t;
    if (degrees == 0 || glm::dot(rotation_axis, rotation_axis) == 0) return Mat3(1.0f);
    return Mat3(glm::rotate(Mat4(1.0f), glm::radians(degrees), glm::normalize(rotation_axis)));
}

float EnvironmentDesc::blend_weight_at(float t) const {
    if (second_file.empty() || !(blend_period_seconds > 0)) return 0.0f;
    return 0.5f - 0.5f * std::cos(2.0f * kPi * t / blend_period_seconds);
}

Vec3 LocalLight::position_at(const Scene& scene, float t) const {
    if (node >= 0) return Vec3(scene.node_world_at(node, t)[3]);
    return path ? path->sample(t) : position;
}

// glTF points spot lights (and cameras) along the node's −Z axis, transformed
// by the node's world matrix and normalized.
Vec3 LocalLight::axis_at(const Scene& scene, float t) const {
    if (node < 0) return axis;
    const Vec3 d = Mat3(scene.node_world_at(node, t)) * Vec3(0, 0, -1);
    const float len = glm::length(d);
    return len > 0 ? d / len : Vec3(0, 0, -1);
}

Vec3 SunLight::direction_at(const Scene& scene, float t) const {
    const Vec3 d = Mat3(scene.node_world_at(node, t)) * Vec3(0, 0, 1);  // against the light's −Z
    const float len = glm::length(d);
    return len > 0 ? d / len : Vec3(0, 1, 0);
}

Mat4 Scene::node_world_at(int node, float t) const {
    if (node < 0) return Mat4(1.0f);
    RSL_CHECK_LT(size_t(node), nodes.size());
    Mat4 world = nodes[node].local_at(t).matrix();
    // Loaders refuse cycles, so the walk to the root ends; the bound is a guard.
    size_t depth = 0;
    for (int p = nodes[node].parent; p >= 0; p = nodes[p].parent) {
        RSL_CHECK_LT(depth++, nodes.size());
        world = nodes[p].local_at(t).matrix() * world;
    }
    return world;
}

size_t Scene::vertex_count() const {
    size_t count = 0;
    for (const Part& part : parts) count += part.mesh.vertex_count();
    return count;
}

}  // namespace rsl
