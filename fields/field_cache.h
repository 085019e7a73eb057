#pragma once
// The fields of every part of a scene, baked once and cached on disk.
//
// Cache: one .rslf file per part and kind in a cache folder (default
// <scene folder>/.rsl-cache), named <scene>.<part index>-<part name>.<kind>.
// <key>.rslf where key = FNV-64 of (format version, mesh hash, parameters):
// changing the mesh or a parameter selects a new file, and a file that does
// not read back valid (stale, corrupt, foreign) is baked again and replaced.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fields/ovdf.h"
#include "fields/svdf.h"
#include "src/core/scene.h"

namespace rsl {

struct PartFields {
    std::optional<Svdf> svdf;
    std::optional<Ovdf> ovdf;
    std::filesystem::path svdf_file, ovdf_file;
    bool svdf_reused = false, ovdf_reused = false;
};

struct FieldCacheOptions {
    std::filesystem::path directory;  // empty: default_cache_directory(scene source)
    bool svdf_only = false;
    bool verbose = true;  // progress and time left on stderr
    // Also called with (what is baked, fraction of that bake), from the
    // baking threads (thread-safe callbacks only); a field read from the
    // cache reports 1 once.
    std::function<void(const std::string& what, double fraction)> progress;
    SvdfParams svdf;
    OvdfParams ovdf;
};

SvdfParams svdf_params_from(const PrecomputeSettings& settings);
OvdfParams ovdf_params_from(const PrecomputeSettings& settings);
FieldCacheOptions default_field_options(const Scene& scene);
std::filesystem::path default_cache_directory(const std::filesystem::path& scene_file);

// Loads valid cached fields and bakes (then writes) the missing ones.
std::vector<PartFields> bake_or_load_fields(const Scene& scene, const FieldCacheOptions& options);

}  // namespace rsl
