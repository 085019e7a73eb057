#include "tools/assets/primitives.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.h"

namespace rsl::assets {
namespace {

// Outward normal of a profile traversed with the solid on its left.
Vec2 right_normal(Vec2 tangent) { return glm::normalize(Vec2(tangent.y, -tangent.x)); }

float cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

}  // namespace

// ---------------------------------------------------------------- Profile

float Profile::Segment::length() const { return is_arc ? radius * std::abs(sweep) : glm::length(b - a); }

ProfileSample Profile::Segment::at(float fraction) const {
    if (!is_arc) return {a + (b - a) * fraction, right_normal(b - a)};
    const float angle = angle0 + sweep * fraction;
    const Vec2 radial(std::cos(angle), std::sin(angle));
    // Counter-clockwise arcs have the solid inside (normal = radial), clockwise ones outside.
    return {center + radius * radial, sweep > 0 ? radial : -radial};
}

Profile& Profile::line_to(Vec2 end) {
    if (glm::length(end - cursor_) > 1e-7f) {
        Segment s;
        s.a = cursor_;
        s.b = end;
        segments_.push_back(s);
    }
    cursor_ = end;
    return *this;
}

Profile& Profile::arc(Vec2 center, float radians) {
    Segment s;
    s.is_arc = true;
    s.center = center;
    s.radius = glm::length(cursor_ - center);
    s.angle0 = std::atan2(cursor_.y - center.y, cursor_.x - center.x);
    s.sweep = radians;
    segments_.push_back(s);
    cursor_ = s.at(1.0f).point;
    return *this;
}

Profile& Profile::rounded_polyline(const std::vector<Vec2>& points, float fillet_radius) {
    std::vector<Vec2> path{cursor_};
    path.insert(path.end(), points.begin(), points.end());
    for (size_t k = 1; k + 1 < path.size(); ++k) {
        const Vec2 corner = path[k];
        const Vec2 in = corner - path[k - 1], out = path[k + 1] - corner;
        const float len_in = glm::length(in), len_out = glm::length(out);
        const Vec2 u0 = in / len_in, u1 = out / len_out;
        const float turn = std::acos(std::clamp(glm::dot(u0, u1), -1.0f, 1.0f));
        if (turn < 1e-4f) {
            line_to(corner);
            continue;
        }
        // The fillet's tangent points sit `reach` before and after the corner;
        // keep them within half of each leg so neighbouring fillets never overlap.
        float reach = fillet_radius * std::tan(turn / 2);
        reach = std::min({reach, 0.5f * len_in, 0.5f * len_out});
        const float radius = reach / std::tan(turn / 2);
        const float side = cross2(u0, u1) > 0 ? 1.0f : -1.0f;  // left turn: centre on the left
        const Vec2 enter = corner - u0 * reach;
        line_to(enter);
        arc(enter + side * radius * Vec2(-u0.y, u0.x), side * turn);
    }
    line_to(path.back());
    return *this;
}

float Profile::length() const {
    float total = 0;
    for (const Segment& s : segments_) total += s.length();
    return total;
}

std::vector<ProfileSample> Profile::sample(float spacing) const {
    RSL_CHECK(!segments_.empty());
    RSL_CHECK_GT(spacing, 0.0f);
    std::vector<ProfileSample> samples;
    for (const Segment& s : segments_) {
        int steps = std::max(1, int(std::ceil(s.length() / spacing)));
        if (s.is_arc) steps = std::max(steps, int(std::ceil(std::abs(s.sweep) / (kPi / 15))));
        for (int i = samples.empty() ? 0 : 1; i <= steps; ++i) samples.push_back(s.at(float(i) / steps));
    }
    return samples;
}

// ---------------------------------------------------------------- revolve

int segments_for(const std::vector<ProfileSample>& profile, float spacing, int minimum) {
    float r_max = 0;
    for (const ProfileSample& s : profile) r_max = std::max(r_max, s.point.x);
    return std::max(minimum, int(std::ceil(2 * kPi * r_max / spacing)));
}

TriangleMesh revolve(const std::vector<ProfileSample>& profile, int segments) {
    RSL_CHECK_GE(profile.size(), size_t(3));
    RSL_CHECK_GE(segments, 3);
    const bool periodic = glm::length(profile.front().point - profile.back().point) < 1e-6f;
    const size_t rows = periodic ? profile.size() - 1 : profile.size();
    const auto on_axis = [&](size_t i) { return !periodic && profile[i].point.x < 1e-6f; };

    TriangleMesh mesh;
    std::vector<uint32_t> row_start(rows);
    for (size_t i = 0; i < rows; ++i) {
        const ProfileSample& s = profile[i];
        row_start[i] = uint32_t(mesh.positions.size());
        if (on_axis(i)) {
            // A pole: one vertex whose normal is the axis direction.
            mesh.positions.emplace_back(0, s.point.y, 0);
            mesh.normals.emplace_back(0, s.normal.y > 0 ? 1.0f : -1.0f, 0);
            continue;
        }
        for (int j = 0; j < segments; ++j) {
            const float phi = 2 * kPi * j / segments;
            const float c = std::cos(phi), sn = std::sin(phi);
            mesh.positions.emplace_back(s.point.x * c, s.point.y, s.point.x * sn);
            mesh.normals.push_back(glm::normalize(Vec3(s.normal.x * c, s.normal.y, s.normal.x * sn)));
        }
    }
    const auto vertex = [&](size_t i, int j) -> uint32_t {
        return on_axis(i) ? row_start[i] : row_start[i] + uint32_t(j % segments);
    };
    // With the profile's solid on its left and φ turning from +X towards +Z,
    // (row i, j) → (i+1, j) → (i+1, j+1) winds counter-clockwise from outside.
    const size_t bands = periodic ? rows : rows - 1;
    for (size_t i = 0; i < bands; ++i) {
        const size_t next = (i + 1) % rows;
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = vertex(i, j), b = vertex(next, j), c = vertex(next, j + 1), d = vertex(i, j + 1);
            // Next to a pole one triangle of the quad collapses; leave it out.
            if (!on_axis(next)) mesh.indices.insert(mesh.indices.end(), {a, b, c});
            if (!on_axis(i)) mesh.indices.insert(mesh.indices.end(), {a, c, d});
        }
    }
    set_axis_tangents(mesh);
    return mesh;
}

// ---------------------------------------------------------------- solids

TriangleMesh sphere(float radius, float spacing) {
    Profile p(Vec2(0, -radius));
    p.arc(Vec2(0, 0), kPi);
    const auto samples = p.sample(spacing);
    return revolve(samples, segments_for(samples, spacing));
}

TriangleMesh capsule(float radius, float half_length, float spacing) {
    Profile p(Vec2(0, -half_length - radius));
    p.arc(Vec2(0, -half_length), kPi / 2).line_to(Vec2(radius, half_length)).arc(Vec2(0, half_length), kPi / 2);
    const auto samples = p.sample(spacing);
    return revolve(samples, segments_for(samples, spacing));
}

TriangleMesh round_cone(float r_bottom, float r_top, float length, float spacing) {
    RSL_CHECK_GT(length, std::abs(r_bottom - r_top));
    // The common tangent leaves both circles at the angle α above the +r axis
    // with sin α = (r_bottom − r_top) / length.
    const float alpha = std::asin((r_bottom - r_top) / length);
    Profile p(Vec2(0, -r_bottom));
    p.arc(Vec2(0, 0), kPi / 2 + alpha)
        .line_to(Vec2(r_top * std::cos(alpha), length + r_top * std::sin(alpha)))
        .arc(Vec2(0, length), kPi / 2 - alpha);
    const auto samples = p.sample(spacing);
    return revolve(samples, segments_for(samples, spacing));
}

TriangleMesh torus(float major, float minor, float spacing) {
    RSL_CHECK_GT(major, minor);
    Profile p(Vec2(major + minor, 0));
    p.arc(Vec2(major, 0), 2 * kPi);
    auto samples = p.sample(spacing);
    samples.back().point = samples.front().point;  // exact closure marks it periodic
    return revolve(samples, segments_for(samples, spacing));
}

TriangleMesh rounded_box(Vec3 half_extents, float radius, float spacing) {
    RSL_CHECK_GT(radius, 0.0f);
    RSL_CHECK_LE(radius, std::min({half_extents.x, half_extents.y, half_extents.z}));
    const Vec3 core = half_extents - radius;  // the box the rounding sphere's centre sweeps
    // Per axis, lattice coordinates are chosen uniform in arc length across a
    // face: flat over the core, then tan-spaced over the 45° of edge rounding
    // that belongs to this face, so vertices end up evenly spread.
    std::array<std::vector<float>, 3> coords;
    for (int a = 0; a < 3; ++a) {
        const float flat = core[a], arc_len = kPi / 4 * radius;
        const float total = 2 * (flat + arc_len);
        const int cells = std::max(2, int(std::ceil(total / spacing)));
        for (int i = 0; i <= cells; ++i) {
            const float s = total * i / cells - total / 2, m = std::abs(s);
            const float g = m <= flat ? m : flat + radius * std::tan((m - flat) / radius);
            coords[a].push_back(std::copysign(g, s));
        }
    }
    const int nx = int(coords[0].size()), ny = int(coords[1].size()), nz = int(coords[2].size());
    std::vector<int> index(size_t(nx) * ny * nz, -1);  // lattice point → vertex (boundary points only)
    TriangleMesh mesh;
    const auto vertex = [&](int i, int j, int k) -> uint32_t {
        int& slot = index[(size_t(k) * ny + j) * nx + i];
        if (slot < 0) {
            const Vec3 g(coords[0][i], coords[1][j], coords[2][k]);
            const Vec3 inner = glm::clamp(g, -core, core);
            const Vec3 n = glm::normalize(g - inner);
            slot = int(mesh.positions.size());
            mesh.positions.push_back(inner + radius * n);
            mesh.normals.push_back(n);
        }
        return uint32_t(slot);
    };
    const int size[3] = {nx, ny, nz};
    for (int a = 0; a < 3; ++a) {
        // (b, c) chosen so that e_b × e_c = e_a: quads (0,0)→(1,0)→(1,1)→(0,1) wind CCW seen from +a.
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            for (int v = 0; v + 1 < size[c]; ++v)
                for (int u = 0; u + 1 < size[b]; ++u) {
                    const auto at = [&](int du, int dv) {
                        int ijk[3];
                        ijk[a] = side ? size[a] - 1 : 0;
                        ijk[b] = u + du;
                        ijk[c] = v + dv;
                        return vertex(ijk[0], ijk[1], ijk[2]);
                    };
                    uint32_t q[4] = {at(0, 0), at(1, 0), at(1, 1), at(0, 1)};
                    if (!side) std::swap(q[1], q[3]);  // the −a face is seen from the other side
                    mesh.indices.insert(mesh.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
                }
        }
    }
    set_axis_tangents(mesh);
    return mesh;
}

TriangleMesh grid_plane(float size_x, float size_z, int cells_x, int cells_z) {
    RSL_CHECK_GE(cells_x, 1);
    RSL_CHECK_GE(cells_z, 1);
    TriangleMesh mesh;
    for (int k = 0; k <= cells_z; ++k)
        for (int i = 0; i <= cells_x; ++i) {
            mesh.positions.emplace_back(size_x * (float(i) / cells_x - 0.5f), 0, size_z * (float(k) / cells_z - 0.5f));
            mesh.normals.emplace_back(0, 1, 0);
        }
    const auto v = [&](int i, int k) { return uint32_t(k * (cells_x + 1) + i); };
    for (int k = 0; k < cells_z; ++k)
        for (int i = 0; i < cells_x; ++i)  // +Z towards the viewer above: (i,k)→(i,k+1)→(i+1,k+1) is CCW from +Y
            mesh.indices.insert(mesh.indices.end(),
                                {v(i, k), v(i, k + 1), v(i + 1, k + 1), v(i, k), v(i + 1, k + 1), v(i + 1, k)});
    set_axis_tangents(mesh);
    return mesh;
}

// ---------------------------------------------------------------- helpers

void transform_mesh(TriangleMesh& mesh, const Mat4& m) {
    const Mat3 linear(m), normal_matrix = glm::transpose(glm::inverse(linear));
    for (Vec3& p : mesh.positions) p = Vec3(m * Vec4(p, 1));
    for (Vec3& n : mesh.normals) n = glm::normalize(normal_matrix * n);
    for (size_t i = 0; i < mesh.tangents.size(); ++i) {
        const Vec3 t = linear * Vec3(mesh.tangents[i]);
        mesh.tangents[i] = Vec4(Frame::from_normal_tangent(mesh.normals[i], t).x, mesh.tangents[i].w);
    }
}

void append_mesh(TriangleMesh& dst, const TriangleMesh& src) {
    const uint32_t base = uint32_t(dst.positions.size());
    dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
    dst.normals.insert(dst.normals.end(), src.normals.begin(), src.normals.end());
    dst.tangents.insert(dst.tangents.end(), src.tangents.begin(), src.tangents.end());
    // Texture coordinates go along when both meshes have them (or dst is empty).
    if (base == 0 || dst.texcoords.size() == base)
        dst.texcoords.insert(dst.texcoords.end(), src.texcoords.begin(), src.texcoords.end());
    for (uint32_t i : src.indices) dst.indices.push_back(base + i);
}

void set_axis_tangents(TriangleMesh& mesh) {
    mesh.tangents.resize(mesh.normals.size());
    for (size_t i = 0; i < mesh.normals.size(); ++i) {
        const Vec3& n = mesh.normals[i];
        const Vec3 axis = std::abs(n.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
        mesh.tangents[i] = Vec4(Frame::from_normal_tangent(n, axis).x, 1.0f);
    }
}

Mat4 translate_rotate(Vec3 translation, Vec3 axis, float radians) {
    return glm::rotate(glm::translate(Mat4(1), translation), radians, glm::normalize(axis));
}

}  // namespace rsl::assets
