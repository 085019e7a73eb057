#include "src/render/part_fields.h"

#include <map>

#include "src/fields/field_cache.h"
#include "src/render/field_cache_loader.h"
#include "src/render/ovdf_occluder.h"

namespace rsl {

SvdfParams svdf_params(const PrecomputeSettings& settings) { return cache_svdf_params(settings); }

PartFields bake_part_fields(const Scene& scene, const FieldBakeOptions& options) {
    PartFields fields;
    fields.self.resize(scene.parts.size());
    fields.occluder.resize(scene.parts.size());
    const SvdfParams self_params = svdf_params(scene.precompute);
    // One bake per unique mesh; its instances share the pointer.
    for (const MeshInstances& group : group_instances(scene)) {
        const Part& part = scene.parts[size_t(group.parts.front())];
        std::shared_ptr<const Svdf> self;
        std::shared_ptr<const OccluderField> occluder;
        if (options.self_visibility) {
            const std::string what = "SVDF " + part.name;
            self = std::make_shared<const Svdf>(bake_svdf(part.mesh, self_params, nullptr, [&](double f) {
                if (options.progress) options.progress(what, f);
            }));
        }
        // A scene of one part has nobody to shadow.
        if (options.occluders && scene.parts.size() > 1) {
            const std::string what = "OVDF " + part.name;
            occluder = bake_ovdf_occluder(part.mesh, ovdf_params(scene.precompute), [&](double f) {
                if (options.progress) options.progress(what, f);
            });
        }
        for (int p : group.parts) fields.self[size_t(p)] = self, fields.occluder[size_t(p)] = occluder;
    }
    return fields;
}

PartFields load_part_fields(const Scene& scene, const FieldBakeOptions& options, FieldLoadReport* report) {
    if (scene.source.empty() && options.cache_directory.empty()) return bake_part_fields(scene, options);
    if (!options.self_visibility && !options.occluders) {  // no field wanted: the cache is not read
        if (report) *report = FieldLoadReport{};
        return bake_part_fields(scene, options);
    }
    CachedFields cached =
        load_or_bake_fields(scene, options.occluders, options.cache_directory, options.progress);
    PartFields fields;
    fields.self.resize(scene.parts.size());
    fields.occluder.resize(scene.parts.size());
    std::map<const Ovdf*, std::shared_ptr<const OccluderField>> occluder_of;  // one wrapper per unique field
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        if (options.self_visibility) fields.self[p] = std::move(cached.svdf[p]);
        if (!options.occluders || !cached.ovdf[p]) continue;
        std::shared_ptr<const OccluderField>& shared = occluder_of[cached.ovdf[p].get()];
        if (!shared) shared = std::make_shared<const OvdfOccluder>(cached.ovdf[p]);
        fields.occluder[p] = shared;
    }
    if (report) *report = FieldLoadReport{cached.loaded, cached.baked};
    return fields;
}

}  // namespace rsl
