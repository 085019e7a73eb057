#include "src/render/ovdf_lookup.h"
#include "src/shading/ovdf_tables.h"

#include <cmath>

namespace rsl {

OvdfLookup::OvdfLookup(const Ovdf& field)
    : field_(&field),
      tables_(field.model.tables.data()),
      vectors_(field.model.vectors),
      dims_(field.model.dims),
      vdt_resolution_(field.params.vdt_resolution),
      outer_(field.shell_radius(field.params.shells - 1)) {}

void OvdfLookup::locate(const Vec3& point, OvdfPoint& out) const {
    const Ovdf& f = *field_;
    const float d = glm::length(point - f.center);
    out.occluded_area = shading::kOvdfNoAreaBound;
    if (d >= outer_) {
        out.kind = OvdfPoint::Outside;
        return;
    }
    out.cone = ovdf_zoom(d, f.radius).cone;
    // The same sample location as the field's own lookup.
    const OvdfLocation& at = out.at = f.locate(point, d);
    out.pole = at.aligned.z;
    if (d < f.radius && f.receiver_inside(point, d, at)) {
        out.kind = OvdfPoint::Inside;
        return;
    }
    out.occluded_area = f.occluded_area_at(at);
    out.kind = usable() ? OvdfPoint::Located : OvdfPoint::Slow;
}

int OvdfLookup::complete(OvdfPoint& out, OvdfTerm* terms) const {
    if (out.kind != OvdfPoint::Located) return 0;
    const Ovdf& f = *field_;
    const OvdfLocation& at = out.at;
    out.terms = terms;
    int used = 0;
    for (int k = 0; k < 2; ++k) {
        const int shell = at.s0 + k;
        const float ws = k == 0 ? 1.0f - at.fs : at.fs;
        out.shell_weight[k] = ws;
        out.zoom[k] = f.shell_zoom(shell);
        out.term_count[k] = 0;
        if (ws == 0.0f) continue;
        const int first = used;
        const int segment = f.segment_of(shell, at.face, at.ii[0], at.jj[0]);
        if (segment == f.segment_of(shell, at.face, at.ii[3], at.jj[3])) {
            // The usual case: all four samples in one (rectangular) segment.
            OvdfTerm& term = terms[used++];
            term.row_offset = int(size_t(segment) * dims_ * (vectors_ + 1));
            term.mean_weight = ws;
            const float* c[4];
            for (int q = 0; q < 4; ++q) c[q] = f.model.coefficients_of(f.sample_index(shell, at.face, at.ii[q], at.jj[q]));
            const float w0 = ws * at.w[0], w1 = ws * at.w[1], w2 = ws * at.w[2], w3 = ws * at.w[3];
            for (int m = 0; m < vectors_; ++m)
                term.coefficients[m] = w0 * c[0][m] + w1 * c[1][m] + w2 * c[2][m] + w3 * c[3][m];
            out.term_count[k] = 1;
            continue;
        }
        // On a seam: one term per PCA segment among the four samples.
        for (int q = 0; q < 4; ++q) {
            if (at.w[q] == 0.0f) continue;
            const int segment = f.segment_of(shell, at.face, at.ii[q], at.jj[q]);
            const int row_offset = int(size_t(segment) * dims_ * (vectors_ + 1));
            OvdfTerm* term = terms + first;
            while (term != terms + used && term->row_offset != row_offset) ++term;
            if (term == terms + used) {
                term->row_offset = row_offset;
                term->mean_weight = 0.0f;
                for (int m = 0; m < vectors_; ++m) term->coefficients[m] = 0.0f;
                ++used;
            }
            const float* sample = f.model.coefficients_of(f.sample_index(shell, at.face, at.ii[q], at.jj[q]));
            term->mean_weight += at.w[q];
            for (int m = 0; m < vectors_; ++m) term->coefficients[m] += at.w[q] * sample[m];
        }
        for (int t = first; t < used; ++t) {
            terms[t].mean_weight *= ws;
            for (int m = 0; m < vectors_; ++m) terms[t].coefficients[m] *= ws;
        }
        out.term_count[k] = used - first;
    }
    out.kind = OvdfPoint::Prepared;
    return used;
}

}  // namespace rsl
