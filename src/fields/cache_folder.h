#pragma once
// A field cache folder as a whole (`rsl cache`; docs/design/FIELDS.md, "Field
// files and the cache"): its entries, which of them a scene uses, and their
// removal. An entry is a regular file directly in the folder named as the
// cache names field files (<svdf|ovdf>-<16 hex digits>.rslf), or as the old
// per-part naming did (…​.<svdf|ovdf>.<16 hex digits>.rslf, never read).
// Nothing else is ever an entry: not a link, a sub-folder or what is in it, a
// temporary a writer is still writing (.NAME.rsl-tmp-…), or a user's file.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/scene.h"

namespace rsl {

struct CacheEntry {
    std::filesystem::path file;
    std::string kind;          // "svdf" or "ovdf"
    bool current = true;       // false: the old per-part naming, which no version reads
    uintmax_t bytes = 0;
    std::filesystem::file_time_type modified;  // when it was baked (reading it changes nothing)
};

// The cache folder of PLACE: a scene file's (<its folder>/.rsl-cache), a
// folder's .rsl-cache when it has one, else the folder itself. Throws
// rsl::Error naming PLACE when it is none of these.
std::filesystem::path resolve_cache_folder(const std::filesystem::path& place);

// True when `name` is an entry's file name (current or old naming).
bool is_cache_entry_name(const std::string& name, std::string* kind = nullptr, bool* current = nullptr);

// The folder's entries, sorted by name. Throws rsl::Error naming the folder
// when it cannot be read.
std::vector<CacheEntry> list_cache_entries(const std::filesystem::path& folder);

// The field files of `folder` that rendering or baking `scene` (with the
// parameters of its precompute block) reads.
std::vector<std::filesystem::path> cache_files_used_by(const Scene& scene, const std::filesystem::path& folder);

// Removes one entry if it is still an entry of `folder` (a regular file of an
// entry's name, directly in the folder; checked again just before removal);
// a file already gone counts as removed. Returns whether it removed a file.
// Throws rsl::Error naming the file when the system refuses.
bool remove_cache_entry(const std::filesystem::path& folder, const CacheEntry& entry);

}  // namespace rsl
