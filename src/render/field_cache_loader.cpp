#include "src/render/field_cache_loader.h"

#include "src/fields/field_cache.h"

namespace rsl {

SvdfParams cache_svdf_params(const PrecomputeSettings& settings) { return svdf_params_from(settings); }
OvdfParams cache_ovdf_params(const PrecomputeSettings& settings) { return ovdf_params_from(settings); }

CachedFields load_or_bake_fields(const Scene& scene, bool occluders,
                                 const std::filesystem::path& cache_directory,
                                 const std::function<void(const std::string&, double)>& callback) {
    FieldCacheOptions options = default_field_options(scene);
    if (!cache_directory.empty()) options.directory = cache_directory;
    options.svdf_only = !occluders || scene.parts.size() < 2;  // a lone part shadows nobody
    options.progress = callback;
    options.on_write_failure = CacheWriteFailure::Warn;
    const SceneFields fields = bake_or_load_fields(scene, options);
    CachedFields result;
    result.svdf.resize(scene.parts.size());
    result.ovdf.resize(scene.parts.size());
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        // Every instance holds the same pointer: one copy per unique mesh.
        const UniqueFields& u = fields.unique[size_t(fields.unique_of_part[p])];
        result.svdf[p] = u.svdf;
        result.ovdf[p] = u.ovdf;
    }
    result.loaded = fields.count(FieldState::Reused);
    result.baked = fields.count(FieldState::Baked);
    result.unique_meshes = int(fields.unique.size());
    return result;
}

}  // namespace rsl
