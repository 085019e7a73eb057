#pragma once
// What the ground truth and env-rays share about the scene they integrate:
// its materials (a textured material in two lobes, each integrated on its
// own) with the checks both make, its local lights posed at a time, and the
// parallel loop over every vertex (docs/design/TRUTH.md).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "src/brdf/brdf.h"
#include "src/core/progress.h"
#include "src/core/scene.h"
#include "src/formats/vertex_colors.h"

namespace rsl {

struct SceneLobes {
    // Per material: its BRDF, or a textured material's diffuse lobe at unit texture.
    std::vector<std::shared_ptr<const Brdf>> lobe;
    std::vector<std::shared_ptr<const Brdf>> whole;     // make_brdf's: both lobes at unit texture
    std::vector<std::shared_ptr<const Brdf>> specular;  // a textured material's specular lobe, else null
    // Per material: whether its roughness and metallic vary per point
    // (src/brdf/pbr_basis.h); then `at_point` gives the BRDF of a point.
    std::vector<uint8_t> varies;
    // The lobe (whole, or a layered material's diffuse or specular lobe) of
    // `material` at texture coordinates uv.
    std::shared_ptr<const Brdf> at_point(const Scene& scene, int material, const Vec2& uv, bool specular_lobe) const;

    // Throws rsl::Error naming the scene file where a part's material index,
    // normals or (textured) texture coordinates, or a light's radius, is wrong.
    explicit SceneLobes(const Scene& scene);
};

// The scene's local lights at a time: centres, spot axes and cones.
struct PosedLights {
    std::vector<Vec3> positions, axes;
    std::vector<Vec2> cones;  // spot_cone_scale_offset
    void set(const Scene& scene, float t);
};

// The colours of every vertex of every part, in parallel (grain vertices a
// task): shade(part, vertex, specular) gives a vertex's colour, of its
// specular lobe when `specular` (layered parts, SceneLobes::specular). Each
// part's emission at its vertices is added after (src/core/emission.h).
VertexColors shade_every_vertex(const Scene& scene, const SceneLobes& lobes, const std::string& producer, float time,
                                size_t grain, const std::function<Color(int part, int vertex, bool specular)>& shade,
                                const ProgressCallback& progress);

}  // namespace rsl
