// `rsl cache list|prune|clear [PLACE]`: the field cache folder as a whole
// (src/fields/cache_folder.h): its files with sizes and the scenes that use
// them, and their removal by use or age. Only the cache's own field files are
// ever removed: no links, sub-folders, user files or temporaries in writing.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>

#include <fmt/core.h>
#include <fmt/format.h>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/fields/cache_folder.h"
#include "src/formats/scene_file.h"
#include "tools/rsl/command.h"

namespace rsl::cli {
namespace {

namespace fs = std::filesystem;

struct CacheArgs {
    std::string action;
    std::string place = ".";
    std::vector<std::string> scenes;
    std::string older_than;
    bool dry_run = false;
};

// A file time as seconds since the Unix epoch.
std::time_t to_time_t(fs::file_time_type time) {
    const auto system = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
        time - fs::file_time_type::clock::now() + std::chrono::system_clock::now());
    return std::chrono::system_clock::to_time_t(system);
}

std::string date_text(fs::file_time_type time) {
    const std::time_t seconds = to_time_t(time);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    return fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d} UTC", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                       utc.tm_hour, utc.tm_min);
}

// YYYY-MM-DD (midnight UTC) or N days ago ("30d"), as seconds since the epoch.
std::time_t parse_date(const std::string& text) {
    int year = 0, month = 0, day = 0, days = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d%c", &days, &tail) == 2 && tail == 'd' && text == fmt::format("{}d", days) &&
        days >= 0)
        return std::time(nullptr) - std::time_t(days) * 86400;
    if (std::sscanf(text.c_str(), "%4d-%2d-%2d%c", &year, &month, &day, &tail) == 3 && month >= 1 && month <= 12 &&
        day >= 1 && day <= 31 && year >= 1970) {
        std::tm utc{};
        utc.tm_year = year - 1900;
        utc.tm_mon = month - 1;
        utc.tm_mday = day;
        return timegm(&utc);
    }
    throw_error("--older-than {}: expected a date YYYY-MM-DD (UTC) or a number of days, e.g. 30d", text);
}

std::string megabytes(uintmax_t bytes) { return fmt::format("{:.2f} MB", double(bytes) / 1e6); }

// The scene files whose use `list` reports by default: those beside the
// cache folder (where the renderers' default cache lies).
std::vector<fs::path> scenes_beside(const fs::path& folder) {
    std::vector<fs::path> scenes;
    std::error_code error;
    const fs::path parent = folder.has_parent_path() ? folder.parent_path() : fs::path(".");
    for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error)) {
        const std::string extension = it->path().extension().string();
        std::error_code file_error;
        if ((extension == ".json" || extension == ".gltf" || extension == ".glb") && it->is_regular_file(file_error))
            scenes.push_back(it->path());
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

// Per cache file, the scenes (as given) that use it. A scene that cannot be
// read is an error when `strict` (prune: what it uses must not go), else it
// is added to `unread`.
std::map<fs::path, std::vector<std::string>> users(const std::vector<fs::path>& scenes, const fs::path& folder,
                                                   bool strict, std::vector<std::string>* unread = nullptr) {
    std::map<fs::path, std::vector<std::string>> used;
    for (const fs::path& scene_file : scenes) {
        try {
            const Scene scene = load_scene(scene_file);
            for (const fs::path& file : cache_files_used_by(scene, folder))
                used[file.lexically_normal()].push_back(scene_file.string());
        } catch (const Error& e) {
            if (strict) throw_error("--scene {}: {} (nothing was removed)", scene_file.string(), e.what());
            if (unread) unread->push_back(scene_file.filename().string());
        }
    }
    return used;
}

void list_cache(const CacheArgs& args, const fs::path& folder) {
    const std::vector<CacheEntry> entries = list_cache_entries(folder);
    std::vector<fs::path> scenes(args.scenes.begin(), args.scenes.end());
    if (scenes.empty()) scenes = scenes_beside(folder);
    const bool given = !args.scenes.empty();
    std::vector<std::string> unread;
    const auto used = users(scenes, folder, false, &unread);
    uintmax_t total = 0;
    for (const CacheEntry& entry : entries) total += entry.bytes;
    fmt::print("{}: {} field files, {}\n", folder.string(), entries.size(), megabytes(total));
    for (const CacheEntry& entry : entries) {
        const auto found = used.find(entry.file.lexically_normal());
        std::string use = found != used.end() ? fmt::format("{}", fmt::join(found->second, ", "))
                                              : entry.current ? "no scene of those read uses it"
                                                              : "old per-part naming, never read";
        fmt::print("  {}  {:>10}  {}  {}\n", entry.file.filename().string(), megabytes(entry.bytes),
                   date_text(entry.modified), use);
    }
    if (scenes.size() > unread.size()) {
        std::vector<std::string> names;
        for (const fs::path& scene : scenes)
            if (std::find(unread.begin(), unread.end(), scene.filename().string()) == unread.end())
                names.push_back(scene.filename().string());
        fmt::print("scenes read: {}\n", fmt::join(names, ", "));
    }
    // A scene given by name that fails is worth its reason; a .json beside the cache may be no scene at all.
    if (!unread.empty())
        fmt::print("{}: {} (rsl info FILE says why)\n", given ? "not read" : "not scenes, or not readable",
                   fmt::join(unread, ", "));
}

void prune_cache(const CacheArgs& args, const fs::path& folder, bool clear) {
    if (!clear && args.scenes.empty() && args.older_than.empty())
        throw_error("rsl cache prune: give --scene SCENE (keep what those scenes use) and/or --older-than DATE");
    const bool by_date = !args.older_than.empty();
    const std::time_t before = by_date ? parse_date(args.older_than) : 0;
    std::vector<fs::path> scenes(args.scenes.begin(), args.scenes.end());
    const auto used = users(scenes, folder, true);
    size_t removed = 0, kept = 0;
    uintmax_t freed = 0;
    for (const CacheEntry& entry : list_cache_entries(folder)) {
        bool remove = true;
        if (!clear) {
            if (!scenes.empty() && used.count(entry.file.lexically_normal())) remove = false;
            if (by_date && to_time_t(entry.modified) >= before) remove = false;
        }
        if (!remove) {
            ++kept;
            continue;
        }
        if (args.dry_run || remove_cache_entry(folder, entry)) {
            ++removed;
            freed += entry.bytes;
            fmt::print("{}{}\n", args.dry_run ? "would remove " : "removed ", entry.file.string());
        }
    }
    // Temporaries of writers that are gone; those of running writers stay.
    if (clear && !args.dry_run) remove_stale_temporaries(folder / "x");
    fmt::print("{}: {} {} field files ({}), {} kept\n", folder.string(), args.dry_run ? "would remove" : "removed",
               removed, megabytes(freed), kept);
}

RegisterCommand cache_command({"cache",
    "The field cache: list its files (sizes, dates, the scenes that use them), prune by use or age, clear", 75,
    [](CLI::App& app) {
        auto args = std::make_shared<CacheArgs>();
        app.add_option("action", args->action,
                       "list: the cache's field files; prune: remove those no --scene uses and/or older than "
                       "--older-than; clear: remove every field file")
            ->required()
            ->check(CLI::IsMember({"list", "prune", "clear"}));
        app.add_option("place", args->place,
                       "A scene file (its cache: .rsl-cache beside it), a folder holding a .rsl-cache, or a cache "
                       "folder (default: the current folder)")
            ->capture_default_str();
        app.add_option("--scene", args->scenes,
                       "list: the scenes whose use to show (default: the scene files beside the cache); prune: keep "
                       "every file these scenes use");
        app.add_option("--older-than", args->older_than,
                       "prune: remove files baked before DATE (YYYY-MM-DD, UTC) or more than N days ago (Nd); with "
                       "--scene, only files both unused and older");
        app.add_flag("--dry-run,-n", args->dry_run, "prune, clear: say what would be removed, remove nothing");
        app.footer("Only field files (svdf-KEY.rslf, ovdf-KEY.rslf, and the old per-part names) directly in the "
                   "cache folder are removed: never a link, a sub-folder, another file, or a file another process "
                   "is still writing. A render or bake that needs a removed file bakes it again.");
        app.callback([args] {
            const fs::path folder = resolve_cache_folder(args->place);
            if (args->action == "list") list_cache(*args, folder);
            else prune_cache(*args, folder, args->action == "clear");
        });
    }});

}  // namespace
}  // namespace rsl::cli
