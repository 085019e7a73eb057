#pragma once
// Fast OVDF lookups for the renderer: Ovdf::distance (OvdfBlend::
// AlignedCoefficients) split into the part that depends on the receiver point
// only — shell pair and weights, cube face and the four samples' blended PCA
// coefficients, the receiver's aligned pole frame — and the part that depends
// on the light: the plane point, four bilinear taps per shell and one
// reconstruction per PCA segment the samples fall in. A vertex is looked up
// for every light (30–100) with the same point, so the first part is computed
// once per (vertex, occluder) and the per-light cost drops to a few 4-row dot
// products.
//
// Most (vertex, occluder, light) lookups never need the blend: the part lies
// in its bounding cone seen from the vertex, and unshadowed() decides from
// that cone alone that a light's square lies beyond it (the lookup's last
// bound), so a renderer prepares a point only when some light needs it. Of
// the rest, the lights whose square is wider than the cone take the
// small-occluder rule (shading::ovdf_small_occluder_weight), which needs
// only the point's cone, blended occluded area and pole — the CPU renderer
// gets those for many vertices at once (Ovdf::locate_near) — and no pole
// frame or coefficients: a renderer locates a point fully, then completes
// it with its terms, only when a narrower light needs the tables.
//
// It mirrors src/fields/ovdf.cpp (same formulas, same order of blending) and is
// pinned to Ovdf::distance by tests/render/ovdf_lookup_test.cpp.

#include "src/fields/ovdf.h"
#include "src/fields/visibility_distance_table.h"
#include "src/shading/ovdf_tables.h"
#include "src/shading/ovdf_small_occluder.h"

namespace rsl {

// One PCA segment's share of a lookup at one of the two bracketing shells:
// its samples' coefficients blended with their bilinear and shell weights.
struct OvdfTerm {
    static constexpr int kMaxVectors = 12;
    int row_offset = 0;     // start of the segment's table
    float mean_weight = 0;  // weight of the mean row (the blend weights of the samples in this segment)
    float coefficients[kMaxVectors];
};

// The receiver-point half of a lookup (occluder frame).
struct OvdfPoint {
    static constexpr int kMaxTerms = 8;  // two shells × four samples in four segments at most
    // Outside: beyond the outer shell (distance "no boundary"); Inside: within
    // the part (fully shadowed); Located: the samples' location and the pole
    // frame, the terms not yet (complete()); Prepared: terms are ready; Slow:
    // the field's own lookup.
    enum Kind : int { Outside = 0, Inside = 1, Prepared = 2, Slow = 3, Located = 4 };
    int kind = Outside;
    // Plane radius of the part's bounding cone seen from the point (kOvdfNoCone
    // inside the bounding sphere): lights with |p| − cone ≥ h are unshadowed.
    float cone = kOvdfNoCone;
    // The samples' blended occluded area (Ovdf::occluded_area_at) of a
    // Located, Prepared or Slow point; no bound otherwise (inside stays dark).
    float occluded_area = shading::kOvdfNoAreaBound;
    Vec3 pole{0, 0, 1};  // unit direction from the point to the part's center (the pole frame's z)
    OvdfLocation at;  // where the point lies among the samples, and its pole frame (Located, Prepared)
    float shell_weight[2] = {0, 0};
    OvdfZoom zoom[2];              // per bracketing shell: its table zoom and cone
    int term_count[2] = {0, 0};    // terms of each shell, shell 0's first
    const OvdfTerm* terms = nullptr;
};

class OvdfLookup {
public:
    explicit OvdfLookup(const Ovdf& field);
    const Ovdf& field() const { return *field_; }
    // Whether prepare() applies at all (few enough PCA vectors); otherwise
    // located points are looked up by the field itself.
    bool usable() const { return field_->model.vectors <= OvdfTerm::kMaxVectors; }

    // The point half of a lookup: Outside, or Prepared with its sample blend
    // written to `terms` (room for OvdfPoint::kMaxTerms, which must outlive
    // the point's lookups; Slow when !usable()). Returns the terms used.
    // locate() then complete() is the same in two steps.
    int prepare(const Vec3& point, OvdfPoint& q, OvdfTerm* terms) const {
        locate(point, q);
        return complete(q, terms);
    }
    // The point's location: Outside, Inside, Slow, or Located (no terms yet).
    void locate(const Vec3& point, OvdfPoint& q) const;
    // A Located point's terms (prepare()'s); other kinds stay as they are.
    int complete(OvdfPoint& q, OvdfTerm* terms) const;
    // Whether a lookup of `q` for squares of half-edge h needs its terms:
    // a Located point whose occluder is not small for h.
    static bool needs_terms(const OvdfPoint& q, float h) {
        return q.kind == OvdfPoint::Located && shading::ovdf_small_occluder_weight(q.cone, h, q.occluded_area) < 1.0f;
    }

    // Whether the lookup certainly gives 1 for a light whose direction has
    // cosine `cos_to_center` with the pole and a square of half-edge h: the
    // square lies beyond the bound |p| − cone that distance() applies (|p|² =
    // 1 − cos in the pole frame). Branch-free, for vectorized loops.
    static bool unshadowed(float cos_to_center, float cone, float half_edge) {
        return shading::ovdf_unshadowed(cos_to_center, cone, half_edge);  // the GPU's test too
    }

    // The visible fraction of the square of half-edge h around a unit light
    // direction: the small-occluder rule where the square is wider than the
    // part's cone, the distance's straight-edge rule bounded by the
    // silhouette's area where it is narrower, faded between; equals
    // field().visible_fraction up to rounding. `q` must not need its terms
    // (needs_terms).
    float visible_fraction(const OvdfPoint& q, const Vec3& point, const Vec3& light, float h) const {
        const float w = shading::ovdf_small_occluder_weight(q.cone, h, q.occluded_area);
        const float radial = w > 0.0f ? shading::ovdf_pole_radial(glm::dot(light, q.pole)) : 0.0f;
        const float small = w > 0.0f ? shading::ovdf_small_occluder_fraction(radial, q.occluded_area, q.cone, h) : 1.0f;
        if (w >= 1.0f) return small;
        const float tables =
            shading::ovdf_area_bound(visible_fraction_from_distance(distance(q, point, light), h), q.occluded_area, h);
        return shading::ovdf_fade_small_occluder(tables, small, w);
    }

    // Blended signed distance (plane units) for a unit light direction; equals
    // field().distance(point, light, AlignedCoefficients) up to rounding.
    // `q` must be Outside, Inside, Prepared or Slow.
    float distance(const OvdfPoint& q, const Vec3& point, const Vec3& light) const {
        if (q.kind == OvdfPoint::Outside) return kVdtNoBoundaryDistance;
        if (q.kind == OvdfPoint::Inside) return -kVdtNoBoundaryDistance;
        if (q.kind == OvdfPoint::Slow) return field_->distance(point, light, OvdfBlend::AlignedCoefficients);
        // The usual vector counts get fully unrolled row blends.
        switch (vectors_) {
            case 4: return prepared_distance<4>(q, light);
            case 6: return prepared_distance<6>(q, light);
            case 8: return prepared_distance<8>(q, light);
            default: return prepared_distance<0>(q, light);
        }
    }

private:
    // The light's plane point in the point's aligned pole frame.
    static Vec2 plane_point(const OvdfPoint& q, const Vec3& light) {
        const Frame& f = q.at.aligned;
        return lookup_plane_point(Vec3(glm::dot(light, f.x), glm::dot(light, f.y), glm::dot(light, f.z)));
    }
    // distance() of a Prepared point; V = the PCA vector count (0: vectors_).
    template <int V>
    float prepared_distance(const OvdfPoint& q, const Vec3& light) const {
        const int vectors = V > 0 ? V : vectors_, stride = vectors + 1;
        const Vec2 p = plane_point(q, light);
        const float radial = std::sqrt(p.x * p.x + p.y * p.y);
        const int n = vdt_resolution_;
        float distance = 0;
        const OvdfTerm* term = q.terms;
        for (int k = 0; k < 2; ++k) {
            if (q.term_count[k] == 0) continue;
            const float zoom = q.zoom[k].zoom;
            const BilinearTaps taps = bilinear_taps(n, zoom * p);
            const size_t below = size_t(n) * stride;
            const float* const weights = &taps.weight[0];
            float value = 0;  // × shell weight, table units
            for (const OvdfTerm* end = term + q.term_count[k]; term != end; ++term) {
                // bilinear_taps' four texels: (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1).
                const float* r00 = tables_ + term->row_offset + size_t(taps.index[0]) * stride;
                const float* const rows[4] = {r00, r00 + stride, r00 + below, r00 + below + stride};
                value += blend_rows_dot<V>(rows, weights, term->mean_weight, term->coefficients, vectors);
            }
            distance += shading::ovdf_weighted_plane_distance(value, q.shell_weight[k], q.zoom[k], radial);
        }
        return shading::ovdf_receiver_distance(distance, radial, q.cone);  // the receiver's own cone (Ovdf::distance)
    }

    const Ovdf* field_;
    const float* tables_;
    int vectors_, dims_, vdt_resolution_;
    float outer_;
};

}  // namespace rsl
