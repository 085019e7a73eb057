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
    // Per block of texels and channel, the first moment M = Σ L Ω ω, so that
    // Σ L Ω max(0, n·ω) = max(0, n·M) wherever the block lies on one side of
    // n's horizon (the cosine is linear in ω): a block is one texel up to
    // kMaxDirectResolution, several above, and only blocks that straddle a
    // horizon approximate. Structure of arrays, dark blocks left out.
    const int side = environment.resolution();
    const int block = (side + kMaxDirectResolution - 1) / kMaxDirectResolution;
    const int blocks = (side + block - 1) / block;
    std::vector<DVec3> moments(size_t(6 * blocks * blocks) * 3, DVec3(0.0));
    for (int k = 0; k < environment.texel_count(); ++k) {
        const Color e = environment.radiance(k) * environment.solid_angle(k);
        if (e == Color(0)) continue;
        const CubeTexel t = environment.texel(k);
        const size_t b = size_t((t.face * blocks + t.j / block) * blocks + t.i / block) * 3;
        const DVec3 d(environment.texel_direction(k));
        for (int c = 0; c < 3; ++c) moments[b + size_t(c)] += double(e[c]) * d;
    }
    std::vector<float> x[3], y[3], z[3];
    for (size_t b = 0; b < moments.size(); b += 3) {
        if (moments[b] == DVec3(0.0) && moments[b + 1] == DVec3(0.0) && moments[b + 2] == DVec3(0.0)) continue;
        for (int c = 0; c < 3; ++c) {
            x[c].push_back(float(moments[b + size_t(c)].x));
            y[c].push_back(float(moments[b + size_t(c)].y));
            z[c].push_back(float(moments[b + size_t(c)].z));
        }
    }
    const size_t texels = x[0].size();
    tbb::parallel_for(size_t(0), map.nodes.size(), [&](size_t node) {
        const Vec3 n = map.node_direction(int(node));
        double sr = 0, sg = 0, sb = 0;
        for (size_t first = 0; first < texels; first += 256) {  // float runs, summed in double
            float fr = 0, fg = 0, fb = 0;
            for (size_t k = first; k < std::min(first + 256, texels); ++k) {
                fr += std::max(n.x * x[0][k] + n.y * y[0][k] + n.z * z[0][k], 0.0f);
                fg += std::max(n.x * x[1][k] + n.y * y[1][k] + n.z * z[1][k], 0.0f);
                fb += std::max(n.x * x[2][k] + n.y * y[2][k] + n.z * z[2][k], 0.0f);
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
