#pragma once
// The compressed occluder field (src/fields/ovdf.h) as the renderer's OccluderField.
#include <algorithm>
#include <functional>
#include <numbers>
#include <memory>

#include "src/fields/ovdf.h"
#include "src/render/part_fields.h"

namespace rsl {

OvdfParams ovdf_params(const PrecomputeSettings& settings);

class OvdfOccluder final : public OccluderField {
public:
    explicit OvdfOccluder(std::shared_ptr<const Ovdf> field, OvdfBlend blend = OvdfBlend::AlignedCoefficients)
        : field_(std::move(field)), blend_(blend) {}
    float visible_fraction(const Vec3& point, const Vec3& light, float half_edge) const override {
        return field_->visible_fraction(point, light, half_edge, blend_);
    }
    BoundingSphere reach() const override {
        return BoundingSphere{field_->center, field_->radius * field_->params.outer_radius};
    }
    // Trilinear blending reads the two shells bracketing the distance (inside
    // the inner shell: the inner two) and, on each, the four samples around
    // the direction, at most a cube cell's diagonal (√2·2/N radians at a face
    // center, less elsewhere) away.
    float footprint(float d_min, float d_max) const override {
        const Ovdf& f = *field_;
        const int last = f.params.shells - 1;
        const int lo = std::min(int(std::clamp(f.shell_coordinate(d_min), 0.0f, float(last))), last - 1);
        const int hi = std::min(int(std::clamp(f.shell_coordinate(d_max), 0.0f, float(last))), last - 1) + 1;
        const float radial = std::max(f.shell_radius(hi), d_max) - std::min(f.shell_radius(lo), d_min);
        return radial + f.shell_radius(hi) * 2.0f * std::numbers::sqrt2_v<float> / float(f.params.cube_resolution);
    }
    const Ovdf& field() const { return *field_; }
    OvdfBlend blend() const { return blend_; }

private:
    std::shared_ptr<const Ovdf> field_;
    OvdfBlend blend_;
};

// The field of an occluder that both renderers look up in two halves
// (OvdfLookup) and cull by its bounding cone: a compressed OVDF blended by
// coefficients with few enough PCA vectors, when `fast_occluder_lookups`
// (RenderOptions); null for every other field.
const Ovdf* split_lookup_field(const OccluderField* field, bool fast_occluder_lookups);

std::shared_ptr<const OccluderField> bake_ovdf_occluder(const TriangleMesh& mesh, const OvdfParams& params,
                                                        const std::function<void(double)>& progress = {});

}  // namespace rsl
