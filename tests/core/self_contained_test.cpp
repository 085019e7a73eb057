// A plain clone is self-contained: every scene under assets/scenes loads from
// a copy of the repository's tracked files plus what the build generates,
// with no ../shared beside it (assets/README.md).
#include <catch2/catch.hpp>

#include <fstream>

#include "tests/test_support.h"

namespace fs = std::filesystem;

TEST_CASE("every scene under assets/scenes loads from a copy of the repository alone", "[scene][cli][clone]") {
    const fs::path base = rsl::test::scratch_dir("clone");
    const fs::path root = base / "rsl";
    const fs::path list = base / "tracked.txt";
    const auto [git_status, git_output] =
        rsl::test::run_command("git -C '" + std::string(RSL_SOURCE_DIR) + "' ls-files -z > '" + list.string() + "'");
    if (git_status != 0) {
        WARN("SKIPPED: the source tree is not a git checkout (" << git_output << ")");
        return;
    }
    std::ifstream in(list, std::ios::binary);
    std::string name;
    size_t copied = 0;
    while (std::getline(in, name, '\0')) {
        const fs::path from = fs::path(RSL_SOURCE_DIR) / name;
        if (!fs::is_regular_file(from)) continue;  // a tracked file deleted in the working tree
        fs::create_directories((root / name).parent_path());
        fs::copy_file(from, root / name);
        ++copied;
    }
    REQUIRE(copied > 100);
    // What the `generated_assets` target does at build time.
    const auto [assets_status, assets_output] = rsl::test::run_rsl("assets --out '" + (root / "assets/generated").string() + "'");
    INFO(assets_output);
    REQUIRE(assets_status == 0);
    REQUIRE_FALSE(fs::exists(base / "shared"));  // where ../shared would sit for assets/scenes/../../../shared

    size_t scenes = 0;
    for (const auto& entry : fs::directory_iterator(root / "assets/scenes")) {
        if (entry.path().extension() != ".json") continue;
        ++scenes;
        const auto [status, output] = rsl::test::run_rsl("info '" + entry.path().string() + "'");
        INFO(entry.path().filename() << ":\n" << output);
        CHECK(status == 0);
    }
    CHECK(scenes >= 6);
}
