#include "src/lightfit/irradiance.h"

#include <tbb/parallel_for.h>

#include "src/core/error.h"
#include "src/shading/diffuse_light.h"

namespace rsl {

Vec3 IrradianceMap::node_direction(int index) const {
    const int row = resolution + 1;
    const int face = index / (row * row), j = (index / row) % row, i = index % row;
    const float step = 2.0f / float(resolution);
    return CubeMap::face_direction(face, -1.0f + step * float(i), -1.0f + step * float(j));
}

Color IrradianceMap::at(const Vec3& normal) const {
    const shading::CubeNodeTaps taps = shading::cube_node_taps(normal, resolution);
    const float wx = taps.weight.x, wy = taps.weight.y;
    const Color* n = nodes.data() + taps.first;
    return (1.0f - wy) * ((1.0f - wx) * n[0] + wx * n[1]) + wy * ((1.0f - wx) * n[taps.row] + wx * n[taps.row + 1]);
}

IrradianceMap irradiance_map(const CubeMap& environment, int resolution) {
    RSL_CHECK(resolution >= 1);
    IrradianceMap map;
    map.resolution = resolution;
    map.nodes.assign(size_t(6 * (resolution + 1) * (resolution + 1)), Color(0));
    // The texels as structure of arrays, radiance × solid angle, dark ones left out.
    std::vector<float> x, y, z, r, g, b;
    for (int k = 0; k < environment.texel_count(); ++k) {
        const Color e = environment.radiance(k) * environment.solid_angle(k);
        if (e == Color(0)) continue;
        const Vec3 d = environment.texel_direction(k);
        x.push_back(d.x), y.push_back(d.y), z.push_back(d.z);
        r.push_back(e.r), g.push_back(e.g), b.push_back(e.b);
    }
    const size_t texels = x.size();
    tbb::parallel_for(size_t(0), map.nodes.size(), [&](size_t node) {
        const Vec3 n = map.node_direction(int(node));
        double sr = 0, sg = 0, sb = 0;
        for (size_t first = 0; first < texels; first += 256) {  // float runs, summed in double
            float fr = 0, fg = 0, fb = 0;
            for (size_t k = first; k < std::min(first + 256, texels); ++k) {
                const float c = std::max(n.x * x[k] + n.y * y[k] + n.z * z[k], 0.0f);
                fr += c * r[k], fg += c * g[k], fb += c * b[k];
            }
            sr += fr, sg += fg, sb += fb;
        }
        map.nodes[node] = Color(float(sr), float(sg), float(sb));
    });
    return map;
}

void add_directional_irradiance(IrradianceMap& map, const Vec3& direction, const Color& irradiance) {
    for (size_t node = 0; node < map.nodes.size(); ++node)
        map.nodes[node] += irradiance * std::max(glm::dot(map.node_direction(int(node)), direction), 0.0f);
}

}  // namespace rsl
