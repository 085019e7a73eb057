#pragma once
// The renderer's door to the fields stage's on-disk cache (src/fields/field_cache.h,
// the files `rsl bake` writes): load every unique mesh's valid cached
// SVDF/OVDF and bake (then write) only the missing ones, with progress on
// stderr. Parts that share a mesh (instances) share one field: the per-part
// pointers below are copies of one pointer.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "src/fields/ovdf.h"
#include "src/fields/svdf.h"
#include "src/core/scene.h"

namespace rsl {

struct CachedFields {
    std::vector<std::shared_ptr<const Svdf>> svdf;  // per part; null where not asked for
    std::vector<std::shared_ptr<const Ovdf>> ovdf;  // per part; null where not asked for
    int loaded = 0, baked = 0;                      // field files reused / baked and written
    int unique_meshes = 0;                          // fields are per unique mesh, not per part
};

// The same parameters `rsl bake` derives from a scene's precompute settings,
// so that both find the same cache files.
SvdfParams cache_svdf_params(const PrecomputeSettings& settings);
OvdfParams cache_ovdf_params(const PrecomputeSettings& settings);

// Fields of every part of `scene`, in `cache_directory`, or when that is
// empty beside the scene's source file (<scene folder>/.rsl-cache). OVDFs
// only when `occluders` and the scene has more than one part. `callback`, when
// given, hears every bake's progress (FieldCacheOptions::progress). A field
// file that cannot be written costs a warning (rsl::warn), not the render.
CachedFields load_or_bake_fields(const Scene& scene, bool occluders,
                                 const std::filesystem::path& cache_directory = {},
                                 const std::function<void(const std::string&, double)>& callback = {});

}  // namespace rsl
