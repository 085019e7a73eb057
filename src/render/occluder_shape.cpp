#include "src/render/occluder_shape.h"
#include "src/shading/shapes.h"

#include <algorithm>
#include <cmath>

namespace rsl {

namespace {

double triangle_area(const TriangleMesh& mesh, size_t i) {
    const glm::dvec3 a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
        c(mesh.positions[mesh.indices[i + 2]]);
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

}  // namespace

std::optional<OccluderShape> find_rectangle(const TriangleMesh& mesh) {
    if (mesh.triangle_count() == 0) return std::nullopt;
    const BoundingSphere sphere = mesh.bounding_sphere();
    if (!(sphere.radius > 0.0f)) return std::nullopt;
    // The plane of the largest triangle (in double: sums over big grids).
    glm::dvec3 normal(0.0);
    double largest = 0.0, area = 0.0;
    size_t largest_at = 0;
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
            c(mesh.positions[mesh.indices[i + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double twice = glm::length(n);
        area += 0.5 * twice;
        if (twice > largest) largest = twice, normal = n / twice, largest_at = i;
    }
    if (!(largest > 0.0)) return std::nullopt;
    const glm::dvec3 origin(mesh.positions[mesh.indices[0]]);
    const double tolerance = 1e-5 * double(sphere.radius);
    for (const Vec3& p : mesh.positions)
        if (std::abs(glm::dot(glm::dvec3(p) - origin, normal)) > tolerance) return std::nullopt;
    // The rectangle's sides lie along one of the largest triangle's edges:
    // in a grid, any edge but a diagonal; in a quad of two triangles, the
    // edge a triangle's first edge may be is the diagonal (an exporter's
    // index order), so each of the three is tried.
    for (int e = 0; e < 3; ++e) {
        const glm::dvec3 a(mesh.positions[mesh.indices[largest_at + size_t(e)]]);
        const glm::dvec3 b(mesh.positions[mesh.indices[largest_at + size_t((e + 1) % 3)]]);
        glm::dvec3 s = (b - a) - normal * glm::dot(b - a, normal);
        if (!(glm::length(s) > 0.0)) continue;
        s = glm::normalize(s);
        const glm::dvec3 t = glm::cross(normal, s);
        double lo_s = 1e300, hi_s = -1e300, lo_t = 1e300, hi_t = -1e300;
        for (const Vec3& p : mesh.positions) {
            const glm::dvec3 d = glm::dvec3(p) - origin;
            lo_s = std::min(lo_s, glm::dot(d, s)), hi_s = std::max(hi_s, glm::dot(d, s));
            lo_t = std::min(lo_t, glm::dot(d, t)), hi_t = std::max(hi_t, glm::dot(d, t));
        }
        const double rectangle = (hi_s - lo_s) * (hi_t - lo_t);
        if (!(rectangle > 0.0) || std::abs(area - rectangle) > 1e-3 * rectangle) continue;
        OccluderShape r;
        r.kind = shading::kShapeRectangle;
        r.center = Vec3(origin + s * (0.5 * (lo_s + hi_s)) + t * (0.5 * (lo_t + hi_t)));
        r.s = Vec3(s), r.t = Vec3(t), r.normal = Vec3(normal);
        r.hi = Vec3(float(0.5 * (hi_s - lo_s)), float(0.5 * (hi_t - lo_t)), 0.0f);
        r.lo = -r.hi;
        return r;
    }
    return std::nullopt;
}

std::optional<OccluderShape> find_box(const TriangleMesh& mesh) {
    if (mesh.triangle_count() == 0) return std::nullopt;
    const Bounds box = mesh.bounds();
    const Vec3 size = box.hi - box.lo;
    if (!(size.x > 0.0f && size.y > 0.0f && size.z > 0.0f)) return std::nullopt;
    const float tolerance = 1e-5f * glm::length(size);
    // Each triangle's three vertices on one face plane of the box.
    double area = 0.0;
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        bool on_face = false;
        for (int axis = 0; axis < 3 && !on_face; ++axis)
            for (const float plane : {box.lo[axis], box.hi[axis]}) {
                bool all = true;
                for (int k = 0; k < 3; ++k) all = all && std::abs(mesh.positions[mesh.indices[i + k]][axis] - plane) <= tolerance;
                on_face = on_face || all;
            }
        if (!on_face) return std::nullopt;
        area += triangle_area(mesh, i);
    }
    const double surface = 2.0 * (double(size.x) * size.y + double(size.y) * size.z + double(size.z) * size.x);
    if (std::abs(area - surface) > 1e-3 * surface) return std::nullopt;
    OccluderShape r;
    r.kind = shading::kShapeBox;
    r.lo = box.lo, r.hi = box.hi;
    return r;
}

OccluderShape find_occluder_shape(const TriangleMesh& mesh) {
    if (const std::optional<OccluderShape> r = find_rectangle(mesh)) return *r;
    if (const std::optional<OccluderShape> b = find_box(mesh)) return *b;
    return OccluderShape{};
}

}  // namespace rsl
