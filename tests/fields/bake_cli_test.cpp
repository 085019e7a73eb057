// End to end through the `rsl` program: `rsl bake` on a tiny two-part scene
// bakes every field file, a second run reuses them untouched, a corrupted
// file is refused by `rsl info` and baked again by the next `rsl bake`; an
// instanced scene bakes once per unique mesh, and in shards.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "src/fields/field_file.h"
#include "tests/formats/gltf_builder.h"
#include "tests/interrupted_run.h"
#include "tests/special_files.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

// A 4×4 ground of four triangles around a centre vertex, and a unit box on it
// (quads, fan-triangulated); low settings keep the four bakes in milliseconds.
void write_tiny_scene(const fs::path& dir) {
    write_text(dir / "ground.obj",
               "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv 0 0 0\n"
               "f 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n");
    write_text(dir / "box.obj", kUnitBoxObj);
    write_text(dir / "tiny.json", R"({
  "name": "tiny",
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj" } ],
  "precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } }
})");
}

// The .rslf paths `rsl bake` printed on stdout, one a line, in order.
std::vector<fs::path> printed_field_files(const std::string& output) {
    std::vector<fs::path> files;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (line.size() > 5 && line.compare(line.size() - 5, 5, ".rslf") == 0 && line.find(' ') == std::string::npos)
            files.emplace_back(line);
    return files;
}

std::map<fs::path, std::string> contents_of(const std::vector<fs::path>& files) {
    std::map<fs::path, std::string> contents;
    for (const fs::path& f : files) contents[f] = read_bytes(f);
    return contents;
}

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// The tiny scene's meshes, instanced: a glTF whose tetrahedron three nodes
// use (and a triangle prism one node uses), the box OBJ named by three parts
// with transforms of their own (one scaled), the ground once: 8 parts, 4
// unique meshes, so 8 field files.
void write_instanced_scene(const fs::path& dir) {
    write_tiny_scene(dir);
    GltfBuilder b;
    const int tetrahedron = b.mesh({0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
    const int prism = b.mesh({0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 1, 1, 0, 0, 1, 1},
                             {0, 2, 1, 3, 4, 5, 0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 2, 0, 3, 2, 3, 5});
    b.node({{"name", "tet_a"}, {"mesh", tetrahedron}, {"translation", {1.0, 0.0, 1.0}}});
    b.node({{"name", "tet_b"}, {"mesh", tetrahedron}, {"translation", {-1.0, 0.0, 1.0}}, {"scale", {2.0, 2.0, 2.0}}});
    b.node({{"name", "tet_c"}, {"mesh", tetrahedron}, {"rotation", {0.0, 0.3826834, 0.0, 0.9238795}}});
    b.node({{"name", "prism"}, {"mesh", prism}, {"translation", {0.0, 0.0, -1.5}}});
    b.write_glb(dir / "pieces.glb");
    write_text(dir / "tiny.json", R"({
  "name": "instanced",
  "gltf": "pieces.glb",
  "parts": [ { "name": "ground", "obj": "ground.obj" },
             { "name": "box1", "obj": "box.obj", "transform": { "translation": [1.5, 0, 0] } },
             { "name": "box2", "obj": "box.obj", "transform": { "translation": [-1.5, 0, 0], "scale": 0.5 } },
             { "name": "box3", "obj": "box.obj", "transform": { "rotation_axis_angle": [0, 1, 0, 30] } } ],
  "subdivision": false,
  "precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } }
})");
}

std::set<fs::path> as_set(const std::vector<fs::path>& files) { return {files.begin(), files.end()}; }

}  // namespace

TEST_CASE("rsl bake: bakes, reuses the cache, refuses and rebakes a corrupt file", "[fields][cli]") {
    const fs::path dir = scratch_dir("bake_cli");
    write_tiny_scene(dir);
    const std::string scene = (dir / "tiny.json").string();
    const fs::path cache = dir / ".rsl-cache";  // the default: beside the scene

    // First run: SVDF and OVDF of both parts, all baked, in the default cache folder.
    const auto [status, output] = run_rsl("bake " + scene);
    INFO(output);
    REQUIRE(status == 0);
    const std::vector<fs::path> files = printed_field_files(output);
    REQUIRE(files.size() == 4);
    for (const fs::path& f : files) {
        CHECK(fs::equivalent(f.parent_path(), cache));
        CHECK(f.extension() == ".rslf");
    }
    CHECK(contains(output, "4 field files baked, 0 reused from the cache"));
    CHECK(std::count_if(fs::directory_iterator(cache), fs::directory_iterator(), [](const auto&) { return true; }) == 4);
    // What was written reads back as the fields of the right kind and mesh.
    CHECK(read_field_header(files[0]).kind == FieldKind::Svdf);
    CHECK(read_field_header(files[1]).kind == FieldKind::Ovdf);
    CHECK(read_field_header(files[2]).kind == FieldKind::Svdf);
    CHECK(read_field_header(files[0]).mesh_hash != read_field_header(files[2]).mesh_hash);
    const auto baked = contents_of(files);
    std::map<fs::path, fs::file_time_type> written;
    for (const fs::path& f : files) written[f] = fs::last_write_time(f);

    // Second run: everything from the cache, files untouched.
    {
        const auto [again, text] = run_rsl("bake " + scene);
        INFO(text);
        REQUIRE(again == 0);
        CHECK(printed_field_files(text) == files);
        CHECK(contains(text, "0 field files baked, 4 reused from the cache"));
        CHECK(contains(text, "cached " + files[3].string()));
        CHECK(contents_of(files) == baked);
        for (const fs::path& f : files) CHECK(fs::last_write_time(f) == written[f]);
    }

    // `rsl info` checks a good file ...
    {
        const auto [info_status, text] = run_rsl("info " + files[2].string());
        INFO(text);
        CHECK(info_status == 0);
        CHECK(contains(text, "OK"));
    }
    // ... an OVDF's spans and occluded areas ...
    for (const fs::path& f : files) {
        if (f.filename().string().rfind("ovdf-", 0) != 0) continue;
        const auto [info_status, text] = run_rsl("info " + f.string());
        INFO(text);
        CHECK(info_status == 0);
        CHECK(contains(text, "radial spans   256x256 lines per cube face"));
        CHECK(contains(text, "occluded area  per sample, up to "));
        CHECK_FALSE(contains(text, "up to 0.000 plane"));  // a box shadows something
    }
    // ... and refuses the box's SVDF with one byte flipped, naming the file.
    const fs::path victim = files[2];
    std::string bytes = baked.at(victim);
    bytes[bytes.size() / 2] ^= 0x40;
    write_text(victim, bytes);
    {
        const auto [info_status, text] = run_rsl("info " + victim.string());
        INFO(text);
        CHECK(info_status != 0);
        CHECK(contains(text, victim.string() + ": checksum mismatch"));
    }

    // The next bake (quiet) warns, bakes that one file again and reuses the rest.
    {
        const auto [rebake, text] = run_rsl("bake -q " + scene);
        INFO(text);
        REQUIRE(rebake == 0);
        CHECK(printed_field_files(text) == files);
        CHECK(contains(text, "rsl: warning: "));
        CHECK(contains(text, victim.string() + ": checksum mismatch"));
        const auto now = contents_of(files);
        for (const fs::path& f : files) {
            INFO(f);
            CHECK(now.at(f) == baked.at(f));  // the bake is deterministic: the same bytes as the first time
            if (f != victim) CHECK(fs::last_write_time(f) == written[f]);
        }
        CHECK(run_rsl("info " + victim.string()).first == 0);
    }
    // Not quiet, the summary counts the rebake: one file, the others reused.
    {
        std::string again = baked.at(files[1]);
        again[again.size() / 3] ^= 0x01;
        write_text(files[1], again);
        const auto [rebake, text] = run_rsl("bake " + scene);
        INFO(text);
        REQUIRE(rebake == 0);
        CHECK(contains(text, "1 field files baked, 3 reused from the cache"));
    }
}

TEST_CASE("rsl bake --help explains the cache", "[fields][cli]") {
    const auto [status, text] = run_rsl("bake --help");
    INFO(text);
    CHECK(status == 0);
    CHECK(contains(text, ".rsl-cache"));
    CHECK(contains(text, "reuses every cached file"));
    CHECK(contains(text, "baked again"));
}

TEST_CASE("rsl bake killed at any moment: no partial field file, and the rerun reuses and sweeps", "[fields][cli][fault]") {
    const fs::path dir = scratch_dir("bake_killed");
    write_tiny_scene(dir);
    // A 61×61-vertex ground and heavier settings than the tiny scene's, so
    // that a bake lasts long enough (about 0.35 s on a quiet machine) to be cut.
    write_text(dir / "ground.obj", grid_obj(60, 2.0));
    write_text(dir / "tiny.json", R"({
  "name": "tiny",
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj" } ],
  "precompute": { "svdf": { "resolution": 16, "clusters": 4, "vectors": 2, "supersampling": 2 },
                  "ovdf": { "shells": 6, "cube_resolution": 12, "vdt_resolution": 16, "vectors": 4 } }
})");
    const std::string scene = (dir / "tiny.json").string();
    const fs::path cache = dir / ".rsl-cache";
    const auto final_files = [&] {
        std::vector<fs::path> found;
        if (fs::exists(cache))
            for (const auto& e : fs::directory_iterator(cache))
                if (e.path().filename().string()[0] != '.') found.push_back(e.path());
        return found;
    };
    // Kill (SIGKILL) at growing delays; whatever stands under a final name must be whole.
    int killed = 0;
    for (const double delay : {0.02, 0.05, 0.1, 0.15, 0.2, 0.3}) {
        killed += run_killed(std::string(RSL_RSL_EXECUTABLE) + " bake -q " + scene, {delay}, {}, {}).killed;
        for (const fs::path& f : final_files()) CHECK_NOTHROW(read_field_header(f));  // magic, size, checksum
    }
    CHECK(killed > 0);  // else nothing was cut, and the test proved nothing
    const auto before = contents_of(final_files());
    const auto [status, output] = run_rsl("bake " + scene);
    INFO(output);
    REQUIRE(status == 0);
    CHECK(printed_field_files(output).size() == 4);
    // What the killed runs finished is reused byte for byte; their temporaries are gone.
    for (const auto& [path, bytes] : before) CHECK(read_bytes(path) == bytes);
    CHECK(contains(output, fmt::format("{} reused from the cache", before.size())));
    CHECK(temporaries_in(cache).empty());
    fs::remove_all(dir);
}

TEST_CASE("rsl bake and rsl info: fields per unique mesh, however many parts use it", "[fields][cli][instances]") {
    const fs::path dir = scratch_dir("bake_instances");
    write_instanced_scene(dir);
    const std::string scene = (dir / "tiny.json").string();
    const fs::path cache = dir / ".rsl-cache";
    {
        const auto [status, text] = run_rsl("info " + scene);
        INFO(text);
        REQUIRE(status == 0);
        CHECK(contains(text, "parts:             8"));
        CHECK(contains(text, "unique meshes:     4"));
        CHECK(contains(text, "'tet_a': 4 vertices, 3 parts (tet_a, tet_b, tet_c)"));
        CHECK(contains(text, "'box1': 8 vertices, 3 parts (box1, box2, box3)"));
        CHECK(contains(text, "'ground': 5 vertices, 1 part (ground)"));
        CHECK(contains(text, "not in the cache"));
    }
    const auto [status, output] = run_rsl("bake " + scene);
    INFO(output);
    REQUIRE(status == 0);
    const std::vector<fs::path> files = printed_field_files(output);
    CHECK(files.size() == 8);                // 4 unique meshes × 2 kinds, not 8 parts × 2
    CHECK(as_set(files).size() == 8);
    CHECK(contains(output, "rsl bake: 8 parts, 4 unique meshes"));
    CHECK(contains(output, "8 field files baked, 0 reused from the cache"));
    CHECK(std::count_if(fs::directory_iterator(cache), fs::directory_iterator(), [](const auto&) { return true; }) == 8);
    CHECK(contains(output, "SVDF svdf-"));
    CHECK(contains(output, " kB in RAM"));
    {
        const auto [again, text] = run_rsl("info " + scene);
        INFO(text);
        CHECK(again == 0);
        CHECK(contains(text, "in the cache, "));
        CHECK(!contains(text, "not in the cache"));
    }
}

TEST_CASE("rsl bake --shard: disjoint shares whose union is the full bake, and rendering then bakes nothing",
          "[fields][cli][shard]") {
    const fs::path full = scratch_dir("shard_full"), shared = scratch_dir("shard_shared");
    write_instanced_scene(full);
    write_instanced_scene(shared);
    const auto [status, output] = run_rsl("bake -q " + (full / "tiny.json").string());
    REQUIRE(status == 0);
    const std::vector<fs::path> all = printed_field_files(output);
    REQUIRE(all.size() == 8);

    std::set<fs::path> union_files;
    size_t sum = 0;
    for (const char* shard : {"0/2", "1/2"}) {
        const auto [shard_status, text] = run_rsl("bake --shard " + std::string(shard) + " " + (shared / "tiny.json").string());
        INFO(text);
        REQUIRE(shard_status == 0);
        const std::vector<fs::path> mine = printed_field_files(text);
        CHECK(mine.size() == 4);
        CHECK(contains(text, fmt::format("shard {}: 4 of 8 field files", shard)));
        CHECK(contains(text, "4 field files baked, 0 reused"));  // nothing of the other shard's
        CHECK(contains(text, "left to another shard"));
        sum += mine.size();
        union_files.insert(mine.begin(), mine.end());
    }
    CHECK(union_files.size() == sum);  // disjoint
    REQUIRE(union_files.size() == all.size());
    for (const fs::path& f : all) {
        INFO(f);
        const fs::path twin = shared / ".rsl-cache" / f.filename();
        CHECK(union_files.count(twin) == 1);
        CHECK(read_bytes(twin) == read_bytes(f));
    }
    // The scene renders from the shards' cache with no bake.
    const auto [render_status, text] = run_rsl("render " + (shared / "tiny.json").string() + " -o " +
                                               (shared / "out.exr").string() + " --width 16 --height 12");
    INFO(text);
    CHECK(render_status == 0);
    CHECK(contains(text, "fields: 8 loaded from the cache, 0 baked"));
}

TEST_CASE("rsl bake --shard refuses a bad I/N before loading anything", "[fields][cli][shard][bad-input]") {
    const fs::path dir = scratch_dir("shard_bad");
    write_tiny_scene(dir);
    for (const char* bad : {"2/2", "1/0", "-1/2", "x/2", "3", "1/2/3"}) {
        const auto [status, text] = run_rsl(fmt::format("bake --shard {} {}", bad, (dir / "tiny.json").string()));
        INFO(text);
        CHECK(status == 1);
        CHECK(contains(text, fmt::format("rsl: error: --shard '{}': ", bad)));
        CHECK(contains(text, "expected I/N"));
        CHECK(!fs::exists(dir / ".rsl-cache"));
    }
}

TEST_CASE("rsl bake checks its flags by the scene file's rules, and says when render will not use its fields",
          "[fields][cli][bad-input]") {
    const fs::path dir = scratch_dir("bake_flags");
    write_tiny_scene(dir);
    const std::string scene = (dir / "tiny.json").string() + " -q -o " + (dir / "cache").string();
    // Each once baked files the reader refuses, crashed, exhausted memory or was ignored.
    const std::pair<const char*, const char*> cases[] = {
        {"--vectors 1025", "--vectors 1025: must be an integer from 1 to 256, got 1025 (as precompute.svdf.vectors in a scene file)"},
        {"--shells 1", "--shells 1: must be an integer from 2 to 256, got 1 (as precompute.ovdf.shells"},
        {"--cube-resolution 3", "--cube-resolution 3: must be even, got 3 (as precompute.ovdf.cube_resolution"},
        {"--supersampling 1000", "--supersampling 1000: must be an integer from 1 to 32, got 1000"},
        {"--shells 0", "--shells 0: must be an integer from 2 to 256, got 0"},
        {"--clusters -1", "--clusters -1: must be an integer from 1 to 65536, got -1"},
    };
    for (const auto& [flags, message] : cases) {
        const auto [status, output] = run_rsl("bake " + scene + " " + flags);
        INFO(flags << " -> " << output);
        CHECK(status == 1);
        CHECK(contains(output, message));
        CHECK_FALSE(contains(output, "internal error"));
    }
    CHECK_FALSE(fs::exists(dir / "cache"));
    // The scene file says the same of the same value.
    write_text(dir / "bad.json", R"({"parts": [{"obj": "box.obj"}], "precompute": {"svdf": {"vectors": 1025}}})");
    CHECK(contains(run_rsl("bake " + (dir / "bad.json").string()).second,
                   "precompute.svdf.vectors: must be an integer from 1 to 256, got 1025"));

    // Valid flags that differ from the scene's bake fields `rsl render` will not use: a note says so.
    const auto [status, output] = run_rsl("bake " + scene + " --vectors 3 --svdf-only");
    INFO(output);
    CHECK(status == 0);
    CHECK(contains(output, "rsl bake: note: --vectors 3 (the scene's 2) bake fields that `rsl render` of this scene "
                           "will not use"));
    // Flags equal to the scene's: no note.
    CHECK_FALSE(contains(run_rsl("bake " + scene + " --vectors 2 --svdf-only").second, "note:"));
}

TEST_CASE("rsl bake refuses a FIFO in place of a cached field file, and bakes it again", "[fields][cli][bad-input]") {
    const fs::path dir = scratch_dir("bake_fifo");
    write_tiny_scene(dir);
    const std::string scene = (dir / "tiny.json").string() + " --svdf-only -o " + (dir / "cache").string();
    const auto [status, output] = run_rsl("bake " + scene);
    REQUIRE(status == 0);
    const std::vector<fs::path> files = printed_field_files(output);
    REQUIRE(!files.empty());
    make_fifo(files[0]);
    // Before the fix this waited for a writer forever: 20 s is the test's patience.
    const auto [again, text] = run_command("timeout 20 " + std::string(RSL_RSL_EXECUTABLE) + " bake " + scene);
    INFO(text);
    CHECK(again == 0);
    CHECK(contains(text, files[0].string() + ": is a FIFO (named pipe), not a regular file"));
    CHECK(fs::is_regular_file(files[0]));
}
