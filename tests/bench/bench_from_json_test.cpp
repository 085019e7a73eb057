// `rsl bench --markdown PAGE --from-json FILE`: the page of a saved run names
// that run's machine, commit, date and command; results that cannot say
// where they were measured are refused and nothing is written.
#include <filesystem>

#include <catch2/catch.hpp>

#include "tests/test_support.h"

namespace fs = std::filesystem;

using rsl::test::read_bytes;
using rsl::test::write_text;

TEST_CASE("rsl bench --from-json writes the page of a saved run", "[bench][cli][results-page]") {
    const fs::path dir = rsl::test::scratch_dir("bench_from_json");
    const std::string machine =
        R"({"bench":"machine","hardware_threads":2,"quick":false,"machine":"Test CPU, 2 hardware threads",)"
        R"("commit":"abc1234","date":"2026-01-02","names":["render"],"parts":[],"reaches":[]})";
    const std::string render =
        R"({"bench":"render","case":"robot 30 RSLs","vertices":87651,"lights":30,"shade_seconds":0.083})";

    SECTION("JSON lines, as a run prints them") {
        write_text(dir / "run.jsonl", machine + "\n" + render + "\n");
        const fs::path page = dir / "lines.md";
        auto [status, text] = rsl::test::run_rsl("bench --markdown " + page.string() + " --from-json " +
                                                 (dir / "run.jsonl").string());
        INFO(text);
        REQUIRE(status == 0);
        const std::string written = read_bytes(page);
        CHECK_THAT(written, Catch::Contains("Written by `rsl bench --markdown " + page.string() +
                                            " render` at commit `abc1234` on 2026-01-02, on Test CPU, 2 hardware threads"));
        CHECK_THAT(written, Catch::Contains("| robot 30 RSLs | 87,651 | 30 | 83.0 |"));
    }
    SECTION("a JSON array, as --json-out writes it") {
        write_text(dir / "run.json", "[" + machine + ",\n" + render + "]");
        const fs::path page = dir / "array.md";
        auto [status, text] =
            rsl::test::run_rsl("bench --markdown " + page.string() + " --from-json " + (dir / "run.json").string());
        INFO(text);
        REQUIRE(status == 0);
        CHECK_THAT(read_bytes(page), Catch::Contains("at commit `abc1234`"));
    }
    SECTION("results without a machine line naming the commit are refused, and no page is written") {
        write_text(dir / "old.jsonl", R"({"bench":"machine","hardware_threads":2})" "\n" + render + "\n");
        const fs::path page = dir / "old.md";
        auto [status, text] =
            rsl::test::run_rsl("bench --markdown " + page.string() + " --from-json " + (dir / "old.jsonl").string());
        CHECK(status != 0);
        CHECK_THAT(text, Catch::Contains("no machine line naming the commit"));
        CHECK_FALSE(fs::exists(page));
    }
    SECTION("a line that is not a result is refused, naming the file") {
        write_text(dir / "bad.jsonl", machine + "\n[1, 2]\n");
        auto [status, text] = rsl::test::run_rsl("bench --markdown " + (dir / "bad.md").string() + " --from-json " +
                                                 (dir / "bad.jsonl").string());
        CHECK(status != 0);
        CHECK_THAT(text, Catch::Contains((dir / "bad.jsonl").string() + ": result 2 is array, not an object"));
        write_text(dir / "torn.jsonl", machine + "\n{\"bench\":\n");
        auto [torn_status, torn] = rsl::test::run_rsl("bench --markdown " + (dir / "bad.md").string() +
                                                      " --from-json " + (dir / "torn.jsonl").string());
        CHECK(torn_status != 0);
        CHECK_THAT(torn, Catch::Contains("not the results of rsl bench"));
    }
}
