#include "src/fields/cache_folder.h"

#include <algorithm>
#include <cctype>
#include <system_error>

#include "src/core/error.h"
#include "src/fields/field_cache.h"

namespace rsl {

namespace fs = std::filesystem;

namespace {

bool is_hex16(std::string_view text) {
    return text.size() == 16 &&
           std::all_of(text.begin(), text.end(), [](char c) { return std::isdigit((unsigned char)c) || (c >= 'a' && c <= 'f'); });
}

}  // namespace

bool is_cache_entry_name(const std::string& name, std::string* kind, bool* current) {
    constexpr std::string_view suffix = ".rslf";
    if (name.size() < 4 + 1 + 16 + suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
        return false;
    if (name.front() == '.') return false;  // a temporary, or a hidden file of the user's
    const std::string_view stem(name.data(), name.size() - suffix.size());
    const std::string_view key = stem.substr(stem.size() - 16);
    if (!is_hex16(key)) return false;
    const std::string_view head = stem.substr(0, stem.size() - 17);  // before "<sep><key>"
    const char separator = stem[stem.size() - 17];
    for (const char* k : {"svdf", "ovdf"}) {
        // Current: <kind>-<key>.rslf; old: <scene>.<part index>-<part name>.<kind>.<key>.rslf
        const bool now = separator == '-' && head == k;
        const bool old = separator == '.' && head.size() > 5 && head.substr(head.size() - 5) == std::string(".") + k;
        if (now || old) {
            if (kind) *kind = k;
            if (current) *current = now;
            return true;
        }
    }
    return false;
}

fs::path resolve_cache_folder(const fs::path& place) {
    std::error_code error;
    if (fs::is_regular_file(place, error)) return default_cache_directory(place);
    if (fs::is_directory(place, error)) {
        if (fs::is_directory(place / ".rsl-cache", error)) return place / ".rsl-cache";
        return place;
    }
    throw_error("{}: expected a scene file, a folder holding a .rsl-cache, or a cache folder", place.string());
}

std::vector<CacheEntry> list_cache_entries(const fs::path& folder) {
    std::vector<CacheEntry> entries;
    std::error_code error;
    fs::directory_iterator it(folder, error);
    if (error) throw_error("{}: cannot read the cache folder: {}", folder.string(), error.message());
    for (; it != fs::directory_iterator(); it.increment(error)) {
        if (error) throw_error("{}: cannot read the cache folder: {}", folder.string(), error.message());
        CacheEntry entry;
        entry.file = it->path();
        if (!is_cache_entry_name(entry.file.filename().string(), &entry.kind, &entry.current)) continue;
        std::error_code file_error;
        if (!it->is_regular_file(file_error) || it->is_symlink(file_error)) continue;
        entry.bytes = it->file_size(file_error);
        if (file_error) continue;  // removed by another process meanwhile
        entry.modified = it->last_write_time(file_error);
        if (file_error) continue;
        entries.push_back(entry);
    }
    std::sort(entries.begin(), entries.end(), [](const CacheEntry& a, const CacheEntry& b) { return a.file < b.file; });
    return entries;
}

std::vector<fs::path> cache_files_used_by(const Scene& scene, const fs::path& folder) {
    FieldCacheOptions options = default_field_options(scene);
    options.directory = folder;
    const SceneFields plan = plan_fields(scene, options);
    std::vector<fs::path> files;
    for (const UniqueFields& unique : plan.unique)
        for (const FieldOutcome* outcome : {&unique.svdf_outcome, &unique.ovdf_outcome})
            if (!outcome->file.empty()) files.push_back(outcome->file);
    return files;
}

bool remove_cache_entry(const fs::path& folder, const CacheEntry& entry) {
    // Only a file of an entry's name directly in the folder, and not a link
    // (whose target may lie anywhere): checked here, at removal, not only when listed.
    if (entry.file.parent_path() != folder || !is_cache_entry_name(entry.file.filename().string()))
        throw_internal_error("{} is no entry of the cache folder {}", entry.file.string(), folder.string());
    std::error_code error;
    const fs::file_status status = fs::symlink_status(entry.file, error);
    if (error || !fs::is_regular_file(status)) return false;
    const bool removed = fs::remove(entry.file, error);
    if (error) throw_error("{}: cannot remove: {}", entry.file.string(), error.message());
    return removed;
}

}  // namespace rsl
