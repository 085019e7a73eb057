#include "src/render/ovdf_occluder.h"

namespace rsl {

OvdfParams ovdf_params(const PrecomputeSettings& settings) {
    OvdfParams params;
    params.shells = settings.ovdf_shells;
    params.inner_radius = settings.ovdf_inner_radius;
    params.outer_radius = settings.ovdf_outer_radius;
    params.cube_resolution = settings.ovdf_cube_resolution;
    params.vdt_resolution = settings.ovdf_vdt_resolution;
    params.vectors = settings.ovdf_vectors;
    return params;
}

std::shared_ptr<const OccluderField> bake_ovdf_occluder(const TriangleMesh& mesh, const OvdfParams& params,
                                                        const std::function<void(double)>& progress) {
    auto field = std::make_shared<const Ovdf>(bake_ovdf(mesh, params, nullptr, progress));
    return std::make_shared<const OvdfOccluder>(std::move(field));
}

}  // namespace rsl
