// The cache folder as a whole (src/fields/cache_folder.h): what counts as an
// entry, and that removal never reaches past the folder's own field files.
#include <catch2/catch.hpp>

#include <set>

#include "src/fields/cache_folder.h"
#include "src/fields/field_cache.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

TEST_CASE("cache entry names: the current and the old per-part naming, nothing else", "[fields][cache]") {
    std::string kind;
    bool current = false;
    CHECK(is_cache_entry_name("svdf-60c07ddb693a6d47.rslf", &kind, &current));
    CHECK((kind == "svdf" && current));
    CHECK(is_cache_entry_name("ovdf-bb3df9a59c388629.rslf", &kind, &current));
    CHECK((kind == "ovdf" && current));
    CHECK(is_cache_entry_name("robot.3-arm.ovdf.0123456789abcdef.rslf", &kind, &current));
    CHECK((kind == "ovdf" && !current));
    for (const char* other : {"svdf-60c07ddb693a6d4.rslf", "svdf-60c07ddb693a6d47.rslf.bak", "xvdf-60c07ddb693a6d47.rslf",
                              "svdf-60C07DDB693A6D47.rslf", ".svdf-60c07ddb693a6d47.rsl-tmp-0123456789abcdef-12-0123456789abcdef.rslf",
                              "notes.txt", "svdf_60c07ddb693a6d47.rslf", "my.svdf-60c07ddb693a6d47.rslf"})
        CHECK_FALSE(is_cache_entry_name(other));
    // The names the cache writes are entries.
    CHECK(is_cache_entry_name(svdf_cache_file("c", 42, SvdfParams{}).filename().string()));
    CHECK(is_cache_entry_name(ovdf_cache_file("c", 42, OvdfParams{}).filename().string()));
}

TEST_CASE("removing cache entries touches only the folder's own field files", "[fields][cache]") {
    const fs::path dir = scratch_dir("cache_folder");
    const fs::path cache = dir / ".rsl-cache";
    const fs::path outside = dir / "outside";
    fs::create_directories(cache / "sub");
    fs::create_directories(outside);
    write_text(cache / "svdf-0000000000000001.rslf", "12345");
    write_text(cache / "ovdf-0000000000000002.rslf", "123");
    write_text(cache / "scene.0-box.svdf.0000000000000003.rslf", "1");
    write_text(cache / "notes.txt", "mine");
    write_text(cache / ".ovdf-0000000000000004.rsl-tmp-0123456789abcdef-1-0123456789abcdef.rslf", "being written");
    write_text(cache / "sub" / "svdf-0000000000000005.rslf", "in a sub-folder");
    write_text(outside / "svdf-0000000000000006.rslf", "someone else's");
    fs::create_symlink(outside / "svdf-0000000000000006.rslf", cache / "svdf-0000000000000007.rslf");

    CHECK(resolve_cache_folder(dir) == cache);
    CHECK(resolve_cache_folder(cache) == cache);
    write_text(dir / "scene.json", "{}");
    CHECK(resolve_cache_folder(dir / "scene.json") == cache);
    CHECK(error_of([&] { resolve_cache_folder(dir / "missing"); }).find("missing") != std::string::npos);

    const std::vector<CacheEntry> entries = list_cache_entries(cache);
    std::set<std::string> names;
    for (const CacheEntry& entry : entries) names.insert(entry.file.filename().string());
    CHECK(names == std::set<std::string>{"ovdf-0000000000000002.rslf", "scene.0-box.svdf.0000000000000003.rslf",
                                         "svdf-0000000000000001.rslf"});
    REQUIRE(entries.size() == 3);
    CHECK(entries[0].bytes == 3);
    CHECK_FALSE(entries[1].current);

    for (const CacheEntry& entry : entries) CHECK(remove_cache_entry(cache, entry));
    CHECK(list_cache_entries(cache).empty());
    // A file already gone is no error; a path outside the folder is refused as a bug.
    CHECK_FALSE(remove_cache_entry(cache, entries[0]));
    CacheEntry stray = entries[0];
    stray.file = outside / "svdf-0000000000000006.rslf";
    CHECK_THROWS_AS(remove_cache_entry(cache, stray), InternalError);
    // A link of an entry's name is not removed (nor what it points to), even when asked.
    CacheEntry link = entries[0];
    link.file = cache / "svdf-0000000000000007.rslf";
    CHECK_FALSE(remove_cache_entry(cache, link));
    for (const fs::path& kept : {cache / "notes.txt", cache / "sub" / "svdf-0000000000000005.rslf",
                                 outside / "svdf-0000000000000006.rslf",
                                 cache / ".ovdf-0000000000000004.rsl-tmp-0123456789abcdef-1-0123456789abcdef.rslf"})
        CHECK(fs::exists(kept));
    CHECK(fs::is_symlink(cache / "svdf-0000000000000007.rslf"));
}
