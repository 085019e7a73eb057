// Issue 43, end to end through the `rsl` program: a full disk fails the
// render, naming the output and the reason; a cache folder that cannot be
// written costs a render a warning (the fields baked in memory serve) and
// fails a bake, naming the field file and the reason; two bakes that are
// both PID 1 (separate PID namespaces) share one cache folder.
#include <catch2/catch.hpp>

#include "tests/interrupted_run.h"
#include "tests/private_mounts.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

constexpr const char* kLightPrecompute =
    R"({ "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
         "ovdf": { "shells": 2, "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } })";

}  // namespace

TEST_CASE("rsl render onto a full disk fails, naming the output and the reason, and installs nothing",
          "[render][cli][full-disk]") {
    const fs::path dir = scratch_dir("render_full_disk");
    write_killable_scene(dir, 8, kLightPrecompute);
    const fs::path full = dir / "full";
    fs::create_directories(full);
    const auto render = [&](const fs::path& exr) {
        return run_rsl(fmt::format("render {} -q --lights 4 -o {} --width 500 --height 400",
                                   (dir / "scene.json").string(), exr.string()));
    };
    // Room for the EXR and half the PNG preview (tmpfs counts whole pages), as in the issue.
    const auto [probe_status, probe_text] = render(dir / "probe.exr");
    INFO(probe_text);
    REQUIRE(probe_status == 0);
    const size_t room = (fs::file_size(dir / "probe.exr") + 8191) / 4096 * 4096 + fs::file_size(dir / "probe.png") / 2;
    REQUIRE(fs::file_size(dir / "probe.png") > 16384);
    std::string refused;
    const auto result = in_child([&] { return mount_private_tmpfs(full, 4 << 20); }, [&]() -> std::string {
        if (const std::string filled = fill_leaving(full, room); !filled.empty()) return filled;
        const auto [status, text] = render(full / "mid.exr");
        std::string problems;
        if (status != 1) problems += fmt::format("status {}; ", status);
        if (!contains(text, (full / "mid.png").string())) problems += "the message does not name the preview; ";
        if (!contains(text, "No space left on device")) problems += "the message gives no reason; ";
        if (fs::exists(full / "mid.png"))
            problems += fmt::format("mid.png installed ({} bytes); ", fs::file_size(full / "mid.png"));
        for (const fs::path& left : temporaries_in(full)) problems += "left " + left.filename().string() + "; ";
        return problems.empty() ? "" : text + "\n" + problems;
    }, refused);
    if (!result) {
        WARN("SKIPPED: cannot mount a small tmpfs here (" << refused << "); the full-disk render did not run");
        return;
    }
    CHECK(*result == "");
}

TEST_CASE("a cache folder that cannot be written: rsl render warns and renders, rsl bake fails naming the file",
          "[render][cli][cache]") {
    const fs::path dir = scratch_dir("render_unwritable_cache");
    write_killable_scene(dir, 8, kLightPrecompute);
    // A file where the cache folder should be: root, as in CI's containers,
    // writes into any read-only folder, but not under a file.
    write_text(dir / ".rsl-cache", "not a folder");
    const fs::path exr = dir / "out.exr";
    const auto [render_status, render_text] = run_rsl(fmt::format(
        "render {} -q --lights 4 -o {} --width 32 --height 24", (dir / "scene.json").string(), exr.string()));
    INFO(render_text);
    CHECK(render_status == 0);
    CHECK(fs::exists(exr));
    CHECK(contains(render_text, "warning"));
    CHECK(contains(render_text, (dir / ".rsl-cache" / "svdf-").string()));  // the target, not a temporary
    CHECK(contains(render_text, "Not a directory"));
    CHECK(!contains(render_text, ".rsl-tmp-"));

    const auto [bake_status, bake_text] = run_rsl(fmt::format("bake -q {}", (dir / "scene.json").string()));
    INFO(bake_text);
    CHECK(bake_status == 1);
    CHECK(contains(bake_text, (dir / ".rsl-cache" / "").string()));
    CHECK(contains(bake_text, ".rslf"));
    CHECK(contains(bake_text, "Not a directory"));
    CHECK(!contains(bake_text, ".rsl-tmp-"));
    CHECK(!contains(bake_text, "does not exist"));
}

TEST_CASE("two rsl bake runs, each PID 1 of its own PID namespace, share one cache folder",
          "[render][cli][pid-namespace]") {
    const fs::path dir = scratch_dir("bake_pid_namespaces");
    write_killable_scene(dir, 20, kLightPrecompute);
    const auto [probe, probe_text] = run_command("unshare -pf --mount-proc true");
    if (probe != 0) {
        WARN("SKIPPED: no PID namespaces here (" << probe_text << "); the shared-cache collision test did not run");
        return;
    }
    const std::string bake = fmt::format("unshare -pf --mount-proc {} bake -q {} >/dev/null", RSL_RSL_EXECUTABLE,
                                         (dir / "scene.json").string());
    for (int run = 0; run < 6; ++run) {
        fs::remove_all(dir / ".rsl-cache");
        const auto [status, text] = run_command(
            fmt::format("{{ {0} & a=$!; {0} & b=$!; wait $a; s=$?; wait $b; exit $((s | $?)); }}", bake));
        INFO("run " << run << "\n" << text);
        CHECK(status == 0);
        CHECK(text.empty());
        CHECK(temporaries_in(dir / ".rsl-cache").empty());
    }
}
