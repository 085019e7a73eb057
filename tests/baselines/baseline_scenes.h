#pragma once
// Small analytic scenes and skies the baseline tests share: a ground plane
// under a floating roof that shadows it, and a sky with a bright sun.
#include <map>
#include <string>
#include <vector>

#include "src/core/envmap.h"
#include "src/core/scene.h"
#include "src/formats/vertex_colors.h"
#include "tests/trace/trace_test_scenes.h"

namespace rsl::test {

// trace_test_scenes.h's plane, lifted to height `y`.
inline TriangleMesh make_plane(float size, int cells, float y, const std::string& name) {
    TriangleMesh mesh = make_plane(size, cells, name);
    for (Vec3& p : mesh.positions) p.y = y;
    return mesh;
}

// trace_test_scenes.h's part, at the identity rest transform.
inline void add_part(Scene& scene, TriangleMesh mesh, int material) {
    add_part(scene, std::move(mesh), Transform{}, material);
}

inline MaterialDesc material(const std::string& model, std::map<std::string, std::vector<float>> params) {
    MaterialDesc m;
    m.name = model;
    m.model = model;
    m.params = std::move(params);
    return m;
}

// A ground plane under a smaller floating plane that shadows it.
inline Scene make_shadow_scene(bool glossy) {
    Scene scene;
    scene.name = "shadow";
    scene.source = "shadow.json";
    scene.materials.push_back(material("lambert", {{"albedo", {0.8f, 0.6f, 0.4f}}}));
    scene.materials.push_back(
        glossy ? material("blinn_phong", {{"kd", {0.3f, 0.3f, 0.3f}}, {"ks", {0.5f, 0.5f, 0.5f}}, {"exponent", {40}}})
               : material("lambert", {{"albedo", {0.5f, 0.5f, 0.5f}}}));
    add_part(scene, make_plane(4.0f, 8, 0.0f, "ground"), 1);
    add_part(scene, make_plane(1.0f, 2, 0.7f, "roof"), 0);
    scene.camera.position = Vec3(1.0f, 3.0f, 2.5f);
    scene.camera.target = Vec3(0);
    return scene;
}

// Sky with a bright sun: shadows and all frequencies.
inline CubeMap make_sky(int n) {
    CubeMap map(n);
    const Vec3 sun = glm::normalize(Vec3(0.3f, 0.9f, 0.2f));
    for (int k = 0; k < map.texel_count(); ++k) {
        const Vec3 d = map.texel_direction(k);
        const float sky = d.y > 0 ? 0.4f + 0.6f * d.y : 0.1f;
        const float glow = glm::dot(d, sun) > 0.97f ? 40.0f : 0.0f;
        map.radiance(k) = Color(sky + glow, sky + 0.9f * glow, 1.2f * sky + 0.7f * glow);
    }
    return map;
}

inline std::vector<Color> flatten(const VertexColors& colors) {
    std::vector<Color> flat;
    for (const auto& part : colors.parts) flat.insert(flat.end(), part.begin(), part.end());
    return flat;
}

}  // namespace rsl::test
