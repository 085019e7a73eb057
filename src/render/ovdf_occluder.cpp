#include "src/render/ovdf_occluder.h"
#include "src/render/ovdf_lookup.h"

#include "src/render/field_cache_loader.h"

namespace rsl {

OvdfParams ovdf_params(const PrecomputeSettings& settings) { return cache_ovdf_params(settings); }

std::shared_ptr<const OccluderField> bake_ovdf_occluder(const TriangleMesh& mesh, const OvdfParams& params,
                                                        const std::function<void(double)>& progress) {
    auto field = std::make_shared<const Ovdf>(bake_ovdf(mesh, params, nullptr, progress));
    return std::make_shared<const OvdfOccluder>(std::move(field));
}

const Ovdf* split_lookup_field(const OccluderField* field, bool fast_occluder_lookups) {
    const auto* ovdf = dynamic_cast<const OvdfOccluder*>(field);
    if (!fast_occluder_lookups || !ovdf || ovdf->blend() != OvdfBlend::AlignedCoefficients) return nullptr;
    return OvdfLookup(ovdf->field()).usable() ? &ovdf->field() : nullptr;
}

}  // namespace rsl
