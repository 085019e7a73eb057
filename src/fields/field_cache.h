#pragma once
// The fields of a scene, baked once per unique (mesh, field parameters) and
// cached on disk.
//
// Instances: parts whose meshes have equal content (mesh_hash: positions,
// normals, tangents, indices — a glTF mesh used by several nodes, the same
// OBJ named by several scene parts, or a mesh repeated by hand) share one
// field of each kind. It is baked once in the mesh's own frame, stored in one
// file and held once in memory; every part applies its own transform when it
// is shaded. The part's name, material and transform are no part of the key.
//
// Cache: one .rslf file per unique field in a cache folder (default
// <scene folder>/.rsl-cache), named <kind>-<key>.rslf with key = FNV-64 of
// (format version, mesh hash, parameters): any scene that uses that mesh with
// those parameters finds the file, and changing the mesh or a parameter
// selects another one. A file that does not read back valid (corrupt,
// foreign, stale) is baked again and replaced. Files of other names (caches
// of earlier versions, named per part) are never read.
//
// Shards: a FieldShard {I, N} bakes only the unique fields whose index, in
// the order of their file names, is I mod N, so N processes (on one machine
// or many, sharing the cache folder) together bake each field exactly once.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "src/fields/ovdf.h"
#include "src/fields/svdf.h"
#include "src/core/scene.h"

namespace rsl {

// Parts that share one mesh (by content), in order of first use.
struct MeshInstances {
    uint64_t mesh_hash = 0;
    std::vector<int> parts;  // ascending; the first one's mesh is baked
};
// Throws rsl::InternalError if two different meshes hash alike (they would
// share a cache file).
std::vector<MeshInstances> group_instances(const Scene& scene);

enum class FieldState { Skipped, Reused, Baked };  // Skipped: not asked for, or another shard's

// One field file of one unique mesh: where it is and what this run did.
struct FieldOutcome {
    std::filesystem::path file;  // empty: the kind is not asked for (svdf_only)
    bool wanted = false;         // asked for and in this shard
    FieldState state = FieldState::Skipped;
    double seconds = 0;      // reading or baking
    size_t disk_bytes = 0;   // of the file (0: it could not be written)
    size_t memory_bytes = 0; // of the field's arrays in RAM
    // A baked field's compression (the tables' size over the compressed
    // size) and its rms error; 0 for a field read from the cache.
    double compression_ratio = 0, rms_error = 0;
};

struct UniqueFields {
    MeshInstances mesh;
    std::shared_ptr<const Svdf> svdf;  // null where skipped
    std::shared_ptr<const Ovdf> ovdf;
    OvdfParams ovdf_params;  // the options' own, an automatic inner radius resolved for this mesh
    FieldOutcome svdf_outcome, ovdf_outcome;
};

struct SceneFields {
    std::vector<UniqueFields> unique;  // in order of first use
    std::vector<int> unique_of_part;   // per part: its entry in `unique`
    int count(FieldState state) const;
};

struct FieldShard {
    int index = 0, count = 1;
    bool all() const { return count == 1; }
};
// "I/N" with integers 0 ≤ I < N; throws rsl::Error naming `option` otherwise.
FieldShard parse_field_shard(const std::string& text, const std::string& option = "--shard");

// What a field file that cannot be written (read-only or full cache folder)
// does to the run: a bake exists for its files and fails; a render needs only
// the fields, baked in memory, and goes on after a warning.
enum class CacheWriteFailure { Fail, Warn };

struct FieldCacheOptions {
    std::filesystem::path directory;  // empty: default_cache_directory(scene source)
    bool svdf_only = false;
    // Called with (what is baked, fraction of that bake), from the baking
    // threads (thread-safe callbacks only); a field read from the cache
    // reports 1 once. Nothing is printed: the tools draw it.
    std::function<void(const std::string& what, double fraction)> progress;
    SvdfParams svdf;
    OvdfParams ovdf;
    FieldShard shard;
    CacheWriteFailure on_write_failure = CacheWriteFailure::Fail;
};

SvdfParams svdf_params_from(const PrecomputeSettings& settings);
OvdfParams ovdf_params_from(const PrecomputeSettings& settings);
FieldCacheOptions default_field_options(const Scene& scene);
std::filesystem::path default_cache_directory(const std::filesystem::path& scene_file);

// The cache file of a mesh's field: <directory>/<svdf|ovdf>-<key>.rslf.
std::filesystem::path svdf_cache_file(const std::filesystem::path& directory, uint64_t mesh_hash,
                                      const SvdfParams& params);
std::filesystem::path ovdf_cache_file(const std::filesystem::path& directory, uint64_t mesh_hash,
                                      const OvdfParams& params);

// Bytes of a field's arrays in memory (what one more shared instance does not add).
size_t memory_bytes(const Svdf& svdf);
size_t memory_bytes(const Ovdf& ovdf);

// The unique meshes, their field files and which of them are the options'
// shard's, without reading or baking anything (every state Skipped).
SceneFields plan_fields(const Scene& scene, const FieldCacheOptions& options);

// Loads valid cached fields and bakes (then writes) the missing ones of the
// options' shard, once per unique mesh.
SceneFields bake_or_load_fields(const Scene& scene, const FieldCacheOptions& options);

}  // namespace rsl
