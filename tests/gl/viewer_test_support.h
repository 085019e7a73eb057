#pragma once
// What the viewer tests share: OBJ files of test meshes, where the viewer's
// initial camera puts a world point, and the display's sRGB curve.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/mesh.h"

namespace rsl::test {

inline void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh) {
    std::ofstream out(path);
    for (const Vec3& p : mesh.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const Vec3& n : mesh.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        out << 'f';
        for (int k = 0; k < 3; ++k) out << ' ' << mesh.indices[3 * t + k] + 1 << "//" << mesh.indices[3 * t + k] + 1;
        out << '\n';
    }
}

// The viewer's view-projection for its initial camera (viewer.cpp: the scene
// camera's eye and target, near/far from the orbit distance).
inline Mat4 viewer_view_projection(const Vec3& eye, const Vec3& target, float fov_degrees, int width, int height) {
    const float distance = glm::length(eye - target);
    return glm::perspective(glm::radians(fov_degrees), float(width) / float(height), 0.01f * distance,
                            100.0f * distance) *
           glm::lookAt(eye, target, Vec3(0, 1, 0));
}

// Pixel (x, y), row 0 at the top, of a world point seen by that camera.
inline Vec2 project(const Vec3& point, const Vec3& eye, const Vec3& target, float fov_degrees, int width, int height) {
    const Vec4 clip = viewer_view_projection(eye, target, fov_degrees, width, height) * Vec4(point, 1.0f);
    const Vec2 ndc = Vec2(clip) / clip.w;
    return Vec2((ndc.x * 0.5f + 0.5f) * width, (0.5f - ndc.y * 0.5f) * height);
}

// The display's sRGB curve (shaders/srgb.glsl) and its inverse, 0..255.
inline float srgb_255(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    return 255.0f * (c < 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f);
}
inline float linear_255(unsigned char v) {
    const float x = v / 255.0f;
    return 255.0f * (x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f));
}

}  // namespace rsl::test
