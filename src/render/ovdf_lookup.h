#pragma once
// Fast OVDF lookups for the renderer: Ovdf::distance (OvdfBlend::
// AlignedCoefficients) split into the part that depends on the receiver point
// only — shell pair and weights, cube face and the four samples' blended PCA
// coefficients, the receiver's aligned pole frame — and the part that depends
// on the light: the plane point, four bilinear taps per shell and two
// reconstructions. A vertex is looked up for every light (30–100) with the
// same point, so the first part is computed once per (vertex, occluder) and
// the per-light cost drops to two 4-row dot products.
//
// It mirrors fields/ovdf.cpp (same formulas, same order of blending) and is
// pinned to Ovdf::distance by tests/render/ovdf_lookup_test.cpp. Receiver
// points whose four samples straddle PCA segments (the field then blends four
// reconstructions) are marked for the field's own lookup.

#include "fields/ovdf.h"
#include "fields/vdt.h"

namespace rsl {

// The receiver-point half of a lookup (occluder frame).
struct OvdfPoint {
    static constexpr int kMaxVectors = 12;
    enum Kind : int { Outside = 0, Fast = 1, Slow = 2 };  // beyond the outer shell: distance "no boundary"
    int kind = Outside;
    int row_offset[2] = {0, 0};  // per bracketing shell: start of its segment's table
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};  // the aligned pole frame
    float mean_weight[2] = {0, 0};             // the shell weight (multiplies the mean row)
    OvdfZoom zoom[2];                          // per bracketing shell: its table zoom and cone
    float coefficients[2][kMaxVectors];        // blended coefficients × shell weight
};

class OvdfLookup {
public:
    explicit OvdfLookup(const Ovdf& field);
    const Ovdf& field() const { return *field_; }
    // Whether the fast path applies at all (few enough PCA vectors).
    bool usable() const { return field_->model.vectors <= OvdfPoint::kMaxVectors; }

    void prepare(const Vec3& point, OvdfPoint& out) const;

    // Blended signed distance (plane units) for a unit light direction; equals
    // field().distance(point, light, AlignedCoefficients) for Fast points.
    float distance(const OvdfPoint& q, const Vec3& point, const Vec3& light) const {
        if (q.kind == OvdfPoint::Outside) return kVdtNoBoundaryDistance;
        if (q.kind == OvdfPoint::Slow) return field_->distance(point, light, OvdfBlend::AlignedCoefficients);
        const Vec3 local(glm::dot(light, q.x), glm::dot(light, q.y), glm::dot(light, q.z));
        const Vec2 p = lookup_plane_point(local);
        const float radial = std::sqrt(p.x * p.x + p.y * p.y);
        const int n = vdt_resolution_, stride = vectors_ + 1;
        const float hi = float(n - 1);
        float distance = 0;
        for (int k = 0; k < 2; ++k) {
            if (q.mean_weight[k] == 0.0f) continue;
            // bilinear_taps (fields/vdt.cpp) at the shell's zoomed table point, inline.
            const float zoom = q.zoom[k].zoom;
            const float u = std::clamp((zoom * p.x + 1.0f) * (0.5f * float(n)) - 0.5f, 0.0f, hi);
            const float v = std::clamp((zoom * p.y + 1.0f) * (0.5f * float(n)) - 0.5f, 0.0f, hi);
            const int i0 = std::min(int(u), n - 2), j0 = std::min(int(v), n - 2);
            const float fx = u - float(i0), fy = v - float(j0);
            const int base = j0 * n + i0;
            const int index[4] = {base, base + 1, base + n, base + n + 1};
            const float weight[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
            const float* table = tables_ + q.row_offset[k];
            const float* c = q.coefficients[k];
            float value = 0;  // × shell weight, table units
            for (int t = 0; t < 4; ++t) {
                const float* row = table + size_t(index[t]) * stride;
                float r = q.mean_weight[k] * row[0];
                for (int m = 0; m < vectors_; ++m) r += c[m] * row[m + 1];
                value += weight[t] * r;
            }
            // ovdf_plane_distance, scaled by the (positive) shell weight.
            distance += std::max(value / zoom, q.mean_weight[k] * (radial - q.zoom[k].cone));
        }
        return distance;
    }

private:
    const Ovdf* field_;
    const float* tables_;
    int vectors_, dims_, vdt_resolution_;
    float outer_;
};

}  // namespace rsl
