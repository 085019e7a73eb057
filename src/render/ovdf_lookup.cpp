#include "src/render/ovdf_lookup.h"

#include <cmath>

#include "src/core/envmap.h"

namespace rsl {

OvdfLookup::OvdfLookup(const Ovdf& field)
    : field_(&field),
      tables_(field.model.tables.data()),
      vectors_(field.model.vectors),
      dims_(field.model.dims),
      vdt_resolution_(field.params.vdt_resolution),
      outer_(field.shell_radius(field.params.shells - 1)) {
    // The cube faces' axes exactly as Ovdf::prepare sets them.
    const float root2 = std::sqrt(2.0f);
    for (int f = 0; f < 6; ++f) {
        face_normal_[f] = CubeMap::face_direction(f, 0, 0);
        face_s_[f] = root2 * CubeMap::face_direction(f, 1, 0) - face_normal_[f];
        face_t_[f] = root2 * CubeMap::face_direction(f, 0, 1) - face_normal_[f];
    }
}

void OvdfLookup::prepare(const Vec3& point, OvdfPoint& out) const {
    const Ovdf& f = *field_;
    const Vec3 v = point - f.center;
    const float d = glm::length(v);
    if (d >= outer_ || !usable()) {
        out.kind = d >= outer_ ? OvdfPoint::Outside : OvdfPoint::Slow;
        return;
    }
    const Vec3 dir = d > 0 ? v / d : Vec3(0, 0, 1);
    const int shells = f.params.shells, n = f.params.cube_resolution;
    const float u = std::clamp(f.shell_coordinate(d), 0.0f, float(shells - 1));
    const int s0 = std::min(int(u), shells - 2);
    const float fs = u - float(s0);
    int face = 0;
    float best = -2;
    for (int k = 0; k < 6; ++k) {
        const float c = glm::dot(dir, face_normal_[k]);
        if (c > best) best = c, face = k;
    }
    const float x = std::clamp((glm::dot(dir, face_s_[face]) / best + 1.0f) * 0.5f * n - 0.5f, 0.0f, float(n - 1));
    const float y = std::clamp((glm::dot(dir, face_t_[face]) / best + 1.0f) * 0.5f * n - 0.5f, 0.0f, float(n - 1));
    const int i0 = std::min(int(x), n - 2), j0 = std::min(int(y), n - 2);
    const float fx = x - float(i0), fy = y - float(j0);
    const int ii[4] = {i0, i0 + 1, i0, i0 + 1}, jj[4] = {j0, j0, j0 + 1, j0 + 1};
    const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};

    const Frame aligned = Frame::from_normal_tangent(-dir, face_s_[face]);
    out.x = aligned.x, out.y = aligned.y, out.z = aligned.z;
    for (int k = 0; k < 2; ++k) {
        const int shell = s0 + k;
        const float ws = k == 0 ? 1.0f - fs : fs;
        const int segment = f.segment_of(shell, face, ii[0], jj[0]);
        if (ws != 0.0f && segment != f.segment_of(shell, face, ii[3], jj[3])) {
            out.kind = OvdfPoint::Slow;  // four reconstructions in their own segments
            return;
        }
        out.row_offset[k] = int(size_t(segment) * dims_ * (vectors_ + 1));
        out.mean_weight[k] = ws;
        out.zoom[k] = f.shell_zoom(shell);
        float* c = out.coefficients[k];
        for (int m = 0; m < vectors_; ++m) c[m] = 0.0f;
        if (ws == 0.0f) continue;
        for (int q = 0; q < 4; ++q) {
            const float* sample = f.model.coefficients_of(f.sample_index(shell, face, ii[q], jj[q]));
            for (int m = 0; m < vectors_; ++m) c[m] += w[q] * sample[m];
        }
        for (int m = 0; m < vectors_; ++m) c[m] *= ws;
    }
    out.kind = OvdfPoint::Fast;
}

}  // namespace rsl
