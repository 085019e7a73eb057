#include "src/render/part_fields.h"

#include "src/render/ovdf_occluder.h"

namespace rsl {

SvdfParams svdf_params(const PrecomputeSettings& settings) {
    SvdfParams params;
    params.resolution = settings.svdf_resolution;
    params.clusters = settings.svdf_clusters;
    params.vectors = settings.svdf_vectors;
    params.supersampling = settings.svdf_supersampling;
    return params;
}

PartFields bake_part_fields(const Scene& scene, const FieldBakeOptions& options) {
    PartFields fields;
    fields.self.resize(scene.parts.size());
    fields.occluder.resize(scene.parts.size());
    const SvdfParams self_params = svdf_params(scene.precompute);
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const Part& part = scene.parts[p];
        if (options.self_visibility) {
            const std::string what = "SVDF " + part.name;
            fields.self[p] = std::make_shared<const Svdf>(bake_svdf(part.mesh, self_params, nullptr, [&](double f) {
                if (options.progress) options.progress(what, f);
            }));
        }
        // A scene of one part has nobody to shadow.
        if (options.occluders && scene.parts.size() > 1) {
            const std::string what = "OVDF " + part.name;
            fields.occluder[p] = bake_ovdf_occluder(part.mesh, ovdf_params(scene.precompute), [&](double f) {
                if (options.progress) options.progress(what, f);
            });
        }
    }
    return fields;
}

}  // namespace rsl
