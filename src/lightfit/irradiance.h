#pragma once
// The exact unshadowed irradiance of an environment over normals,
//
//   E(n) = ∫ L(ω) max(0, n·ω) dω  (+ each sun's irradiance × max(0, n·d)),
//
// tabulated on a cube of normals and read bilinearly (src/shading/diffuse_light.h).
// The renderers shade a part's constant BRDF term with it, the squares
// giving only the shadows' ratio (docs/design/RENDERER.md "Exact diffuse light"),
// so the squares' own error in representing the light does not reach the
// diffuse colour.
#include <vector>

#include "src/core/envmap.h"

namespace rsl {

struct IrradianceMap {
    // M: per face (M + 1)² nodes, face coordinates −1 + 2i/M (cube_node_taps).
    static constexpr int kDefaultResolution = 32;
    int resolution = 0;
    std::vector<Color> nodes;  // 6·(M + 1)², face-major, row j, column i

    bool empty() const { return nodes.empty(); }
    // E at unit normal n (in the map's frame), bilinear between nodes.
    Color at(const Vec3& normal) const;
    // The direction of node `index` (unit).
    Vec3 node_direction(int index) const;
};

// E of every node from the texels of `environment` (each its centre
// direction and solid angle; E is smooth, a texel's own spread is second
// order). Maps above kMaxDirectResolution a side are summed by blocks of
// texels through their first moments, exact but where a block straddles a
// normal's horizon. Parallel over nodes; about 0.2 s on one core.
inline constexpr int kMaxDirectResolution = 64;
IrradianceMap irradiance_map(const CubeMap& environment, int resolution = IrradianceMap::kDefaultResolution);
// Adds a directional source of irradiance `irradiance` (a sun) from unit direction d.
void add_directional_irradiance(IrradianceMap& map, const Vec3& direction, const Color& irradiance);

}  // namespace rsl
