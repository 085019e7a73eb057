// Stress test of one cache folder shared by several processes (docs/FIELDS.md,
// "Sharing a cache"): four processes bake and render one scene from one
// cache at once, a few times over. Every field file must equal a lone bake's
// byte for byte, every render a lone render's, and no temporary may stay.
// Where the machine allows, each process is PID 1 of a PID namespace of its
// own, as in containers that share the cache.
// Registered on its own (tests/CMakeLists.txt, shared-cache-stress): hidden
// from the per-case discovery.
#include <map>

#include <catch2/catch.hpp>

#include "tests/interrupted_run.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

// The field files of a cache folder by name, and their bytes.
std::map<std::string, std::string> field_files(const fs::path& cache) {
    std::map<std::string, std::string> files;
    if (fs::exists(cache))
        for (const auto& e : fs::directory_iterator(cache))
            if (e.path().extension() == ".rslf" && e.path().filename().string()[0] != '.')
                files[e.path().filename().string()] = read_bytes(e.path());
    return files;
}

std::string render_command(const std::string& rsl, const fs::path& scene, const fs::path& exr) {
    fs::path rslv = exr;
    rslv.replace_extension(".rslv");
    return fmt::format("{} render {} -q --lights 4 --width 48 --height 36 -o {} --vertex-out {}", rsl, scene.string(), exr.string(), rslv.string());
}

}  // namespace

TEST_CASE("four processes bake and render one scene from one cache folder at once", "[.shared-cache-stress]") {
    const fs::path lone = scratch_dir("shared_cache_lone"), shared = scratch_dir("shared_cache");
    const std::string precompute =
        R"({ "svdf": { "resolution": 12, "clusters": 4, "vectors": 2, "supersampling": 2 },
             "ovdf": { "shells": 4, "cube_resolution": 8, "vdt_resolution": 12, "vectors": 2 } })";
    write_killable_scene(lone, 16, precompute);
    write_killable_scene(shared, 16, precompute);
    const auto [bake_status, bake_text] = run_rsl("bake -q " + (lone / "scene.json").string());
    INFO(bake_text);
    REQUIRE(bake_status == 0);
    const std::map<std::string, std::string> lone_fields = field_files(lone / ".rsl-cache");
    REQUIRE(lone_fields.size() == 4);  // SVDF and OVDF of two meshes
    const auto [render_status, render_text] = run_command(render_command(RSL_RSL_EXECUTABLE, lone / "scene.json", lone / "out.exr"));
    INFO(render_text);
    REQUIRE(render_status == 0);

    const fs::path scene = shared / "scene.json";
    // Each process PID 1 of a PID namespace of its own, as containers sharing
    // the cache would be, where the machine allows it.
    const bool namespaces = run_command("unshare -pf --mount-proc true").first == 0;
    if (!namespaces) WARN("no PID namespaces here: the four processes share one");
    const std::string rsl = (namespaces ? "unshare -pf --mount-proc " : "") + std::string(RSL_RSL_EXECUTABLE);
    for (int iteration = 0; iteration < 8; ++iteration) {
        fs::remove_all(shared / ".rsl-cache");
        // Two bake then render, two render at once (a render bakes what it misses).
        std::string script = "{ ";
        for (int p = 0; p < 4; ++p) {
            const std::string render = render_command(rsl, scene, shared / fmt::format("out{}.exr", p));
            const std::string bake = p % 2 == 0 ? fmt::format("{} bake -q {} >/dev/null && ", rsl, scene.string()) : "";
            script += fmt::format("({}{}) >{} 2>&1 & p{}=$!; ", bake, render, (shared / fmt::format("log{}", p)).string(), p);
        }
        for (int p = 0; p < 4; ++p) script += fmt::format("wait $p{0} || echo process {0} failed; ", p);
        script += "}";
        const auto [status, text] = run_command(script);
        INFO("iteration " << iteration << "\n" << text);
        CHECK(status == 0);
        CHECK(text.empty());  // no "process N failed"
        for (int p = 0; p < 4; ++p) {
            const std::string log = read_bytes(shared / fmt::format("log{}", p));
            INFO("process " << p << ": " << log);
            CHECK(log.find("error") == std::string::npos);
            CHECK(log.find("warning") == std::string::npos);
            for (const char* extension : {".exr", ".png", ".rslv"}) {
                INFO(extension);
                CHECK(read_bytes(shared / fmt::format("out{}{}", p, extension)) ==
                      read_bytes(lone / fmt::format("out{}", extension)));
            }
        }
        const std::map<std::string, std::string> fields = field_files(shared / ".rsl-cache");
        CHECK(fields.size() == lone_fields.size());
        for (const auto& [name, bytes] : lone_fields) {
            INFO(name);
            CHECK(fields.count(name) == 1);
            CHECK((fields.count(name) == 1 && fields.at(name) == bytes));
        }
        for (const fs::path& left : temporaries_in(shared)) FAIL_CHECK("left behind: " << left.filename().string());
        for (const fs::path& left : temporaries_in(shared / ".rsl-cache"))
            FAIL_CHECK("left behind: " << left.filename().string());
    }
}
