// Triangle-mesh geometry: bounds, normals, tangents, validation.
#include "src/core/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/error.h"

namespace rsl {

namespace {

bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A usable unit vector: finite and of length ≈ 1 (files sometimes store
// unnormalized normals; those are renormalized, zero ones recomputed).
// Lengths are taken in double: a float vector's squared length overflows
// beyond about 1e19 (and normalizing it in float would give zero).
bool is_usable_direction(const Vec3& v) {
    if (!is_finite(v)) return false;
    const DVec3 d(v);
    return glm::dot(d, d) > 1e-12;
}

// Normalized, but a vector that is already unit to float precision is kept
// bit for bit, so that files written from loaded meshes round-trip exactly.
Vec3 unit(const Vec3& v) {
    const float length2 = glm::dot(v, v);
    if (std::abs(length2 - 1.0f) < 1e-6f) return v;
    const DVec3 d(v);
    return Vec3(d / std::sqrt(glm::dot(d, d)));
}

// Twice the triangle's area vector (its direction is the face normal).
Vec3 doubled_area_vector(const TriangleMesh& mesh, size_t triangle) {
    const Vec3& a = mesh.positions[mesh.indices[3 * triangle]];
    const Vec3& b = mesh.positions[mesh.indices[3 * triangle + 1]];
    const Vec3& c = mesh.positions[mesh.indices[3 * triangle + 2]];
    return glm::cross(b - a, c - a);
}

// Whether a triangle has no usable area, judged by its own edges, not the
// mesh's size: a 1 m box beside a 1e6 m ground in one file keeps its faces.
// Its doubled area vector must also have a normal float squared length, or
// its normal could not be normalised.
bool is_degenerate(const TriangleMesh& mesh, size_t triangle, float area_epsilon) {
    const uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                   i2 = mesh.indices[3 * triangle + 2];
    if (i0 == i1 || i1 == i2 || i0 == i2) return true;
    const Vec3& a = mesh.positions[i0];
    const Vec3& b = mesh.positions[i1];
    const Vec3& c = mesh.positions[i2];
    const float longest2 = std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
    const Vec3 doubled = doubled_area_vector(mesh, triangle);
    const float doubled2 = glm::dot(doubled, doubled);
    if (!(doubled2 >= std::numeric_limits<float>::min())) return true;  // also catches NaN
    return !(0.5f * std::sqrt(doubled2) > area_epsilon * longest2);
}

// Area-weighted face normals summed per vertex (not normalized).
std::vector<Vec3> accumulated_face_normals(const TriangleMesh& mesh) {
    std::vector<Vec3> sum(mesh.vertex_count(), Vec3(0));
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 n = doubled_area_vector(mesh, t);  // |n| = 2 × area: the weight
        for (int k = 0; k < 3; ++k) sum[mesh.indices[3 * t + k]] += n;
    }
    return sum;
}

// The tangent the mesh uses at a vertex with unit normal n: the world X axis
// projected into the tangent plane, or the world Z axis within ~8° of ±X, where
// the projection of X vanishes. (A continuous tangent field on a closed surface
// must have singular points; this places them in two small polar caps.)
Vec3 tangent_for_normal(const Vec3& n) {
    constexpr float kPolarCos = 0.99f;
    const Vec3 axis = std::abs(n.x) < kPolarCos ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
    return glm::normalize(axis - n * glm::dot(n, axis));
}

// Removes vertices no triangle references (degenerate triangles leave them
// behind) and renumbers the indices; `kept` (optional) gets each kept
// vertex's former index.
void drop_unreferenced_vertices(TriangleMesh& mesh, std::vector<uint32_t>* kept) {
    constexpr uint32_t kUnused = ~0u;
    std::vector<uint32_t> new_index(mesh.vertex_count(), kUnused);
    for (uint32_t i : mesh.indices) new_index[i] = 0;
    uint32_t next = 0;
    for (size_t v = 0; v < new_index.size(); ++v) {
        if (new_index[v] == kUnused) continue;
        new_index[v] = next;
        if (kept) kept->push_back(uint32_t(v));
        mesh.positions[next] = mesh.positions[v];
        if (v < mesh.normals.size()) mesh.normals[next] = mesh.normals[v];
        if (v < mesh.tangents.size()) mesh.tangents[next] = mesh.tangents[v];
        if (v < mesh.texcoords.size()) mesh.texcoords[next] = mesh.texcoords[v];
        ++next;
    }
    if (next == mesh.vertex_count()) return;
    mesh.positions.resize(next);
    if (mesh.normals.size() > next) mesh.normals.resize(next);
    if (mesh.tangents.size() > next) mesh.tangents.resize(next);
    if (mesh.texcoords.size() > next) mesh.texcoords.resize(next);
    for (uint32_t& i : mesh.indices) i = new_index[i];
}

}  // namespace

Bounds TriangleMesh::bounds() const {
    Bounds b;
    for (const Vec3& p : positions) b.extend(p);
    return b;
}

BoundingSphere TriangleMesh::bounding_sphere() const {
    BoundingSphere sphere;
    const Bounds b = bounds();
    if (b.empty()) return sphere;
    sphere.center = b.center();
    float r2 = 0;
    for (const Vec3& p : positions) r2 = std::max(r2, glm::dot(p - sphere.center, p - sphere.center));
    sphere.radius = std::sqrt(r2);
    return sphere;
}

size_t TriangleMesh::count_degenerate_triangles(float area_epsilon) const {
    size_t count = 0;
    for (size_t t = 0; t < triangle_count(); ++t) count += is_degenerate(*this, t, area_epsilon);
    return count;
}

void compute_normals(TriangleMesh& mesh) {
    std::vector<Vec3> sum = accumulated_face_normals(mesh);
    for (Vec3& n : sum) n = is_usable_direction(n) ? unit(n) : Vec3(0, 1, 0);
    mesh.normals = std::move(sum);
}

void compute_tangents(TriangleMesh& mesh) {
    RSL_CHECK_EQ(mesh.normals.size(), mesh.vertex_count());
    mesh.tangents.resize(mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) mesh.tangents[v] = Vec4(tangent_for_normal(mesh.normals[v]), 1.0f);
}

size_t validate_and_complete(TriangleMesh& mesh, const std::filesystem::path& source,
                             std::vector<uint32_t>* kept_vertices) {
    if (kept_vertices) kept_vertices->clear();
    if (mesh.positions.empty()) throw_file_error(source, "mesh '{}' has no vertices", mesh.name);
    if (mesh.indices.size() % 3 != 0)
        throw_file_error(source, "mesh '{}' has {} indices, not a multiple of 3", mesh.name, mesh.indices.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const Vec3& p = mesh.positions[v];
        if (!is_finite(p))
            throw_file_error(source, "mesh '{}': vertex {} has a non-finite position ({}, {}, {})", mesh.name, v, p.x,
                             p.y, p.z);
    }
    if (!mesh.texcoords.empty() && mesh.texcoords.size() != mesh.positions.size())
        throw_file_error(source, "mesh '{}' has {} texture coordinates for {} vertices", mesh.name,
                         mesh.texcoords.size(), mesh.positions.size());
    for (size_t v = 0; v < mesh.texcoords.size(); ++v)
        if (!std::isfinite(mesh.texcoords[v].x) || !std::isfinite(mesh.texcoords[v].y))
            throw_file_error(source, "mesh '{}': vertex {} has non-finite texture coordinates", mesh.name, v);
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= mesh.vertex_count())
            throw_file_error(source, "mesh '{}': index {} (triangle {}) is {}, out of range for {} vertices", mesh.name,
                             i, i / 3, mesh.indices[i], mesh.vertex_count());
    }

    // Drop degenerate triangles: they have no normal and cast no shadow, and
    // they would make area-weighted normals and Embree unhappy.
    size_t kept = 0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (is_degenerate(mesh, t, 1e-12f)) continue;
        for (int k = 0; k < 3; ++k) mesh.indices[3 * kept + k] = mesh.indices[3 * t + k];
        ++kept;
    }
    const size_t dropped = mesh.triangle_count() - kept;
    mesh.indices.resize(3 * kept);
    mesh.degenerate_dropped += dropped;
    if (kept == 0)
        throw_file_error(source, "mesh '{}' has no triangles{}", mesh.name,
                         dropped ? fmt::format(" ({} degenerate triangles dropped)", dropped) : "");
    drop_unreferenced_vertices(mesh, kept_vertices);

    // Normals: keep valid given ones (renormalized); fill missing or invalid
    // ones with area-weighted normals.
    if (mesh.normals.size() != mesh.vertex_count()) {
        compute_normals(mesh);
    } else {
        std::vector<Vec3> computed;
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            Vec3& n = mesh.normals[v];
            if (is_usable_direction(n)) {
                n = unit(n);
                continue;
            }
            if (computed.empty()) {
                computed = accumulated_face_normals(mesh);
            }
            n = is_usable_direction(computed[v]) ? unit(computed[v]) : Vec3(0, 1, 0);
        }
    }

    // Tangents: keep valid given ones, orthogonalized against the normal;
    // otherwise use the mesh-wide rule of compute_tangents.
    if (mesh.tangents.size() != mesh.vertex_count()) {
        compute_tangents(mesh);
    } else {
        for (size_t v = 0; v < mesh.vertex_count(); ++v) {
            const Vec3& n = mesh.normals[v];
            Vec4& t = mesh.tangents[v];
            const Vec3 given(t);
            Vec3 xyz = given;
            // In double and twice: one float pass leaves a large tangent, or
            // one nearly along the normal, visibly out of the tangent plane.
            // Relative to its length: a small tangent is normalized next.
            if (std::abs(glm::dot(DVec3(n), DVec3(xyz))) > 1e-7 * glm::length(DVec3(xyz))) {
                DVec3 d(xyz);
                for (int pass = 0; pass < 2; ++pass) d -= DVec3(n) * glm::dot(DVec3(n), d);
                xyz = Vec3(d);
            }
            // What is left must be a direction in the plane, not rounding noise
            // of one within about 0.01° of the normal.
            const bool usable = is_usable_direction(xyz) && is_finite(given) && std::isfinite(t.w) &&
                                glm::dot(DVec3(xyz), DVec3(xyz)) > 1e-8 * std::max(1.0, glm::dot(DVec3(given), DVec3(given)));
            if (usable) {
                t = Vec4(unit(xyz), t.w < 0 ? -1.0f : 1.0f);
            } else {
                t = Vec4(tangent_for_normal(n), 1.0f);
            }
        }
    }
    return dropped;
}

}  // namespace rsl
