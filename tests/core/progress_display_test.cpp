// The tools' progress lines (tools/rsl/progress_display.h) on a file, as a
// CI log gets them: a line when a job starts and when it ends, none between
// within ten seconds, none for a job that is done at its first report.
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "tools/rsl/progress_display.h"

namespace {

std::vector<std::string> lines_of(std::FILE* file) {
    std::rewind(file);
    std::vector<std::string> lines;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, file)) {
        std::string line(buffer);
        REQUIRE(!line.empty());
        CHECK(line.back() == '\n');
        CHECK(line.find('\r') == std::string::npos);
        line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

}  // namespace

TEST_CASE("Progress on a file: a line at a job's start and end, none between", "[progress]") {
    std::FILE* file = std::tmpfile();
    REQUIRE(file);
    {
        rsl::cli::ProgressDisplay display(true, file);
        // Two jobs from four threads, 1000 reports each, well inside ten seconds.
        std::vector<std::thread> threads;
        for (int t = 0; t < 4; ++t)
            threads.emplace_back([&display, t] {
                for (int i = 0; i < 1000; ++i) display(t % 2 ? "bake b" : "bake a", (t / 2 * 1000 + i) / 2000.0);
            });
        for (std::thread& thread : threads) thread.join();
        display("bake a", 1.0);
        display("bake a", 0.5);  // after its end: nothing
        display("bake b", 1.0);
        display("cached c", 1.0);  // done at its first report: nothing
        display.note("2 fields baked");
    }
    const std::vector<std::string> lines = lines_of(file);
    std::fclose(file);
    INFO(lines.size() << " lines");
    REQUIRE(lines.size() == 5);
    int starts = 0, ends = 0;
    for (const std::string& line : lines) {
        starts += line.find("%") != std::string::npos;
        ends += line.find(": done in ") != std::string::npos;
        CHECK(line.find("cached c") == std::string::npos);
    }
    CHECK(starts == 2);
    CHECK(ends == 2);
    CHECK(lines.back() == "2 fields baked");
}

TEST_CASE("A quiet display writes nothing", "[progress]") {
    std::FILE* file = std::tmpfile();
    REQUIRE(file);
    {
        rsl::cli::ProgressDisplay display(false, file);
        display("bake", 0.5);
        display("bake", 1.0);
        display.note("done");
    }
    CHECK(lines_of(file).empty());
    std::fclose(file);
}
