// `rsl cache` end to end: a bake's files listed with the scenes that use
// them, pruned by the scenes to keep and by age, cleared; a user's file, a
// sub-folder and a scene that cannot be read stop it from removing more.
#include <catch2/catch.hpp>

#include <set>

#include "src/fields/cache_folder.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

constexpr const char* kTinyPrecompute = R"("precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } })";

std::set<std::string> entry_names(const fs::path& cache) {
    std::set<std::string> names;
    for (const CacheEntry& entry : list_cache_entries(cache)) names.insert(entry.file.filename().string());
    return names;
}

}  // namespace

TEST_CASE("rsl cache lists a bake's files with their scenes, prunes by use and age, and clears", "[fields][cache][cli]") {
    const fs::path dir = scratch_dir("cache_cli");
    write_text(dir / "ground.obj", "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv 0 0 0\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n");
    write_text(dir / "box.obj", kUnitBoxObj);
    write_text(dir / "tiny.json", std::string(R"({ "name": "tiny",
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj" } ], )") +
                                      kTinyPrecompute + "}");
    write_text(dir / "boxonly.json", std::string(R"({ "name": "boxonly", "parts": [ { "name": "box", "obj": "box.obj" } ], )") +
                                         kTinyPrecompute + "}");
    auto [bake_status, bake] = run_rsl("bake -q " + (dir / "tiny.json").string());
    INFO(bake);
    REQUIRE(bake_status == 0);
    const fs::path cache = dir / ".rsl-cache";
    const std::set<std::string> all = entry_names(cache);
    REQUIRE(all.size() == 4);
    write_text(cache / "notes.txt", "mine");

    // The box's two files are both scenes'; the ground's are tiny's alone.
    auto [list_status, list] = run_rsl("cache list " + dir.string());
    INFO(list);
    REQUIRE(list_status == 0);
    CHECK(contains(list, ": 4 field files,"));
    size_t both = 0, tiny_only = 0;
    for (const std::string& name : all) {
        const size_t at = list.find(name);
        REQUIRE(at != std::string::npos);
        const std::string line = list.substr(at, list.find('\n', at) - at);
        both += contains(line, "boxonly.json") && contains(line, "tiny.json");
        tiny_only += !contains(line, "boxonly.json") && contains(line, "tiny.json");
    }
    CHECK((both == 2 && tiny_only == 2));

    // An unreadable scene stops a prune before anything goes.
    write_text(dir / "broken.json", "{ \"parts\": [ { \"name\": \"x\", \"obj\": \"missing.obj\" } ] }");
    auto [broken_status, broken] = run_rsl("cache prune " + dir.string() + " --scene " + (dir / "broken.json").string());
    INFO(broken);
    CHECK(broken_status == 1);
    CHECK(contains(broken, "nothing was removed"));
    CHECK(entry_names(cache) == all);
    fs::remove(dir / "broken.json");

    // Nothing was baked before 2001; everything before tomorrow (a dry run removes nothing).
    auto [old_status, old] = run_rsl("cache prune " + cache.string() + " --older-than 2001-01-01");
    INFO(old);
    CHECK(old_status == 0);
    CHECK(entry_names(cache) == all);
    auto [dry_status, dry] = run_rsl("cache prune " + cache.string() + " --older-than 2999-01-01 --dry-run");
    INFO(dry);
    CHECK(dry_status == 0);
    CHECK(contains(dry, "would remove 4 field files"));
    CHECK(entry_names(cache) == all);
    CHECK(run_rsl("cache prune " + cache.string() + " --older-than yesterday").first == 1);

    // Keep what boxonly uses: the ground's two files go.
    auto [prune_status, prune] = run_rsl("cache prune " + (dir / "tiny.json").string() + " --scene " +
                                         (dir / "boxonly.json").string());
    INFO(prune);
    CHECK(prune_status == 0);
    CHECK(contains(prune, "removed 2 field files"));
    const std::set<std::string> kept = entry_names(cache);
    CHECK(kept.size() == 2);
    auto [again_status, again] = run_rsl("cache list " + cache.string() + " --scene " + (dir / "boxonly.json").string());
    INFO(again);
    for (const std::string& name : kept) CHECK(contains(again, name));

    // Clear removes every field file and nothing else.
    auto [clear_status, clear] = run_rsl("cache clear " + dir.string());
    INFO(clear);
    CHECK(clear_status == 0);
    CHECK(entry_names(cache).empty());
    CHECK(fs::exists(cache / "notes.txt"));
    CHECK(fs::exists(dir / "box.obj"));
    CHECK(fs::exists(dir / "tiny.json"));
}
