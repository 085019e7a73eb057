#include "src/render/field_cache_loader.h"

#include "fields/field_cache.h"

namespace rsl {

SvdfParams cache_svdf_params(const PrecomputeSettings& settings) { return svdf_params_from(settings); }
OvdfParams cache_ovdf_params(const PrecomputeSettings& settings) { return ovdf_params_from(settings); }

CachedFields load_or_bake_fields(const Scene& scene, bool occluders, bool progress,
                                 const std::filesystem::path& cache_directory,
                                 const std::function<void(const std::string&, double)>& callback) {
    FieldCacheOptions options = default_field_options(scene);
    if (!cache_directory.empty()) options.directory = cache_directory;
    options.svdf_only = !occluders || scene.parts.size() < 2;  // a lone part shadows nobody
    options.verbose = progress;
    options.progress = callback;
    std::vector<PartFields> parts = bake_or_load_fields(scene, options);
    CachedFields result;
    result.svdf.resize(parts.size());
    result.ovdf.resize(parts.size());
    for (size_t p = 0; p < parts.size(); ++p) {
        PartFields& f = parts[p];
        if (f.svdf) {
            result.svdf[p] = std::make_shared<const Svdf>(std::move(*f.svdf));
            ++(f.svdf_reused ? result.loaded : result.baked);
        }
        if (f.ovdf) {
            result.ovdf[p] = std::make_shared<const Ovdf>(std::move(*f.ovdf));
            ++(f.ovdf_reused ? result.loaded : result.baked);
        }
    }
    return result;
}

}  // namespace rsl
