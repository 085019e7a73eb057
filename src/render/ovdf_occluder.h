#pragma once
// The compressed occluder field (fields/ovdf.h) as the renderer's OccluderField.
#include <functional>
#include <memory>

#include "fields/ovdf.h"
#include "src/render/part_fields.h"

namespace rsl {

OvdfParams ovdf_params(const PrecomputeSettings& settings);

class OvdfOccluder final : public OccluderField {
public:
    explicit OvdfOccluder(std::shared_ptr<const Ovdf> field, OvdfBlend blend = OvdfBlend::PerSample)
        : field_(std::move(field)), blend_(blend) {}
    float visible_fraction(const Vec3& point, const Vec3& light, float half_edge) const override {
        return field_->visible_fraction(point, light, half_edge, blend_);
    }
    BoundingSphere reach() const override {
        return BoundingSphere{field_->center, field_->radius * field_->params.outer_radius};
    }
    const Ovdf& field() const { return *field_; }

private:
    std::shared_ptr<const Ovdf> field_;
    OvdfBlend blend_;
};

std::shared_ptr<const OccluderField> bake_ovdf_occluder(const TriangleMesh& mesh, const OvdfParams& params,
                                                        const std::function<void(double)>& progress = {});

}  // namespace rsl
