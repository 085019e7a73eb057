#pragma once
// Small analytic scenes for the trace tests: planes, icospheres, Lambert
// materials, cube maps that are constant or lit in a block of texels.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "src/core/envmap.h"
#include "src/core/scene.h"

namespace rsl::test {

// Square grid in the XZ plane (y = 0) of side `size` centered at the origin,
// `cells`×`cells` quads, normal +Y, tangent +X.
inline TriangleMesh make_plane(float size, int cells, const std::string& name = "plane") {
    TriangleMesh mesh;
    mesh.name = name;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            mesh.positions.emplace_back(size * (float(i) / cells - 0.5f), 0.0f, size * (float(j) / cells - 0.5f));
            mesh.normals.emplace_back(0, 1, 0);
            mesh.tangents.emplace_back(1, 0, 0, 1);
        }
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const uint32_t a = j * (cells + 1) + i, b = a + 1, c = a + (cells + 1), d = c + 1;
            // Counter-clockwise seen from +Y: (p1 − p0) × (p2 − p0) points up.
            for (uint32_t index : {a, c, b, b, c, d}) mesh.indices.push_back(index);
        }
    return mesh;
}

// Icosphere of `radius` at the origin, `level` subdivisions (20·4^level
// triangles), with exact sphere normals, outward winding.
inline TriangleMesh make_icosphere(float radius, int level, const std::string& name = "sphere") {
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Vec3> v = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& p : v) p = glm::normalize(p);
    std::vector<uint32_t> f = {0, 11, 5, 0, 5,  1,  0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
        auto mid = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            return midpoint[key] = uint32_t(v.size() - 1);
        };
        std::vector<uint32_t> next;
        for (size_t t = 0; t < f.size(); t += 3) {
            const uint32_t a = f[t], b = f[t + 1], c = f[t + 2];
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            for (uint32_t index : {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}) next.push_back(index);
        }
        f.swap(next);
    }
    TriangleMesh mesh;
    mesh.name = name;
    for (const Vec3& p : v) {
        mesh.positions.push_back(radius * p);
        mesh.normals.push_back(p);
        const Vec3 t = Frame::from_normal(p).x;
        mesh.tangents.emplace_back(t, 1.0f);
    }
    mesh.indices = f;
    return mesh;
}

// A box of half extents h centred at the origin, flat-shaded as exporters
// write one (each face its own vertices and normal: the edges are creases),
// each face split into n × n quads, with tangents and a per-face uv.
inline TriangleMesh make_flat_box(Vec3 h, int n, const std::string& name = "box") {
    TriangleMesh mesh;
    mesh.name = name;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.0f, 1.0f}) {
            Vec3 normal(0), u(0), v(0);
            normal[axis] = sign;
            u[(axis + 1) % 3] = 1;
            v[(axis + 2) % 3] = sign;  // u × v = sign · axis: counter-clockwise seen from outside
            const uint32_t base = uint32_t(mesh.positions.size());
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= n; ++i) {
                    const Vec3 local = normal + (2.0f * i / n - 1) * u + (2.0f * j / n - 1) * v;
                    mesh.positions.push_back(local * h);
                    mesh.normals.push_back(normal);
                    mesh.tangents.emplace_back(u, 1.0f);
                    mesh.texcoords.emplace_back(float(i) / n, float(j) / n);
                }
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const uint32_t a = base + uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
                    for (uint32_t index : {a, b, d, a, d, c}) mesh.indices.push_back(index);
                }
        }
    return mesh;
}

inline MaterialDesc lambert(Color albedo, const std::string& name = "white") {
    MaterialDesc m;
    m.name = name;
    m.model = "lambert";
    m.params["albedo"] = {albedo.r, albedo.g, albedo.b};
    return m;
}

// "glossy": Blinn-Phong with grey kd and ks.
inline MaterialDesc blinn_phong(float kd, float ks, float exponent, const std::string& name = "glossy") {
    MaterialDesc m;
    m.name = name;
    m.model = "blinn_phong";
    m.params = {{"kd", {kd, kd, kd}}, {"ks", {ks, ks, ks}}, {"exponent", {exponent}}};
    return m;
}

// Adds a part with its own node (rest transform) and returns the part index.
inline int add_part(Scene& scene, TriangleMesh mesh, const Transform& rest = {}, int material = 0) {
    SceneNode node;
    node.name = mesh.name;
    node.rest = rest;
    scene.nodes.push_back(node);
    Part part;
    part.name = mesh.name;
    part.mesh = std::move(mesh);
    part.node = int(scene.nodes.size()) - 1;
    part.material = material;
    scene.parts.push_back(std::move(part));
    return int(scene.parts.size()) - 1;
}

inline Scene make_scene(const std::string& name, Color albedo = Color(1)) {
    Scene scene;
    scene.name = name;
    scene.source = name + ".json";
    scene.materials.push_back(lambert(albedo));
    scene.camera.position = Vec3(0, 10, 0.5f);  // above everything: views from above the planes
    scene.camera.target = Vec3(0);
    return scene;
}

inline CubeMap constant_cube(int n, Color radiance) {
    CubeMap map(n);
    for (Color& c : map.radiances()) c = radiance;
    return map;
}

// Black except texels [i0, i1) × [j0, j1) of `face`.
inline CubeMap block_cube(int n, int face, int i0, int i1, int j0, int j1, Color radiance) {
    CubeMap map(n);
    for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) map.radiance(map.index(face, i, j)) = radiance;
    return map;
}

}  // namespace rsl::test
