#include "src/render/ovdf_lookup.h"

#include <cmath>


namespace rsl {

OvdfLookup::OvdfLookup(const Ovdf& field)
    : field_(&field),
      tables_(field.model.tables.data()),
      vectors_(field.model.vectors),
      dims_(field.model.dims),
      vdt_resolution_(field.params.vdt_resolution),
      outer_(field.shell_radius(field.params.shells - 1)) {}

void OvdfLookup::prepare(const Vec3& point, OvdfPoint& out) const {
    const Ovdf& f = *field_;
    const Vec3 v = point - f.center;
    const float d = glm::length(v);
    if (d >= outer_ || !usable()) {
        out.kind = d >= outer_ ? OvdfPoint::Outside : OvdfPoint::Slow;
        return;
    }
    // The same sample location as the field's own lookup.
    const OvdfLocation at = f.locate(point, d);
    const int s0 = at.s0, face = at.face;
    const float fs = at.fs;
    const int* ii = at.ii;
    const int* jj = at.jj;
    const float* w = at.w;
    const Frame& aligned = at.aligned;
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
