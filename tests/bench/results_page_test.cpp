// The page `rsl bench --markdown` writes (tools/bench/results_page.h): every
// figure of the run in its section's table, formatted, with the machine, the
// commit and the command named.
#include <algorithm>

#include <catch2/catch.hpp>

#include "tools/bench/results_page.h"

namespace rsl::bench {
namespace {

using nlohmann::json;

TEST_CASE("The results page tables every line of the run, naming where it was measured", "[bench][results-page]") {
    const std::vector<json> results{
        {{"bench", "machine"}, {"hardware_threads", 2}},
        {{"bench", "render"}, {"case", "robot 30 RSLs"}, {"vertices", 87651}, {"lights", 30},
         {"shade_seconds", 0.0812}, {"fps_shading", 12.315}, {"relative_l2_vs_truth", 0.02137},
         {"objects_relative_l2_vs_truth", 0.0241}, {"worst_part", "shin_l"},
         {"worst_part_relative_l2_vs_truth", 0.109}, {"speedup_shading", 79.04}},
        {{"bench", "render"}, {"case", "kitchen"}, {"skipped", "missing shared assets"}},
        {{"bench", "gl"}, {"case", "BRDF SAT storage steel"}, {"float16_median_relative_error", 0.2}},
        {{"bench", "gl"}, {"case", "robot 30 RSLs"}, {"device", "EGL: OpenGL 4.5 llvmpipe"}, {"vertices", 87651},
         {"cpu_shading_ms", 97.0}, {"gpu_shading_ms", 1474.0}, {"gpu_over_cpu", 15.2},
         {"cpu_occluder_lookups", 1503019}, {"gpu_occluder_lookups", 1503136}, {"gpu_cpu_relative_l2", 9.1e-6},
         {"frame_ms", nullptr}},
        {{"bench", "scale"}, {"plot", "/tmp/out/scale/frame_time.png"}},
        {{"bench", "newbench"}, {"case", "a"}, {"widgets_per_second", 1234.5}, {"label", "x"}},
    };
    const ResultsRun run{"rsl bench --markdown docs/RESULTS.md render gl", "abc123", "Some CPU, 2 hardware threads",
                         "2026-12-05", false};
    const std::string page = results_page(results, run, "/tmp/docs");
    INFO(page);
    CHECK_THAT(page, Catch::Contains("Written by `rsl bench --markdown docs/RESULTS.md render gl` at commit `abc123` "
                                     "on 2026-12-05, on Some CPU, 2 hardware threads; OpenGL: EGL: OpenGL 4.5 llvmpipe"));
    CHECK_THAT(page, !Catch::Contains("--quick"));
    // The render line, each figure in its column's format.
    CHECK_THAT(page, Catch::Contains("| robot 30 RSLs | 87,651 | 30 | 81.2 | 12.3 | 2.14% | 2.41% | `shin_l` 10.9% | 79.0× |"));
    CHECK_THAT(page, Catch::Contains("- skipped: kitchen: missing shared assets"));
    // The GPU table keeps the comparison lines only, and leaves out a column no line fills.
    CHECK_THAT(page, Catch::Contains("| robot 30 RSLs | 87,651 | 97.0 | 1474.0 | 15.2× | 1,503,019 | 1,503,136 | 9.1e-06 |"));
    CHECK_THAT(page, !Catch::Contains("BRDF SAT storage"));
    CHECK_THAT(page, !Catch::Contains("frame ms"));
    // A plot is linked relative to the page; a benchmark without a section gets its numbers.
    CHECK_THAT(page, Catch::Contains("](../out/scale/frame_time.png)"));
    CHECK_THAT(page, Catch::Contains("| a | 1234 |"));
    // Sections follow the page's order (render before gl), whatever the run's.
    CHECK(page.find("## Shading on the CPU") < page.find("## The GPU renderer"));

    const ResultsRun quick{"rsl bench --markdown x.md --quick", "abc", "m", "2026-12-05", true};
    CHECK_THAT(results_page(results, quick, "."), Catch::Contains("These are `--quick` figures"));
}

TEST_CASE("The accuracy table has one row per frame and the error at each K in its own column",
          "[bench][results-page]") {
    std::vector<json> results{{{"bench", "machine"}}};
    for (const int k : {10, 30, 60, 100})
        for (const double t : {0.0, 0.5})
            results.push_back({{"bench", "render-accuracy"}, {"scene", "robot"}, {"environment", "grace"},
                               {"material", "glossy"}, {"time", t}, {"lights", k}, {"precompute", "bench"},
                               {"relative_l2", 0.01 * (1 + t) + 1.0 / k}, {"objects_relative_l2", 0.02 + 1.0 / k},
                               {"worst_part", k == 30 ? "torso" : "shin"}, {"worst_part_relative_l2", 0.1 + 1.0 / k},
                               {"relative_l2_without_occluders", 0.3}});
    const std::string page = results_page(results, {"c", "x", "m", "d", false}, ".");
    INFO(page);
    CHECK_THAT(page, Catch::Contains("| scene | environment | material | t | fields | all, K = 10 | all, K = 30 | "
                                     "all, K = 60 | all, K = 100 | objects, K = 30 | worst part | without OVDF |"));
    // 1/10 + 0.01 = 11%, 1/30 + 0.01 = 4.33%, ...; the objects and the worst part at K = 30.
    CHECK_THAT(page, Catch::Contains("| robot | grace | glossy | 0 | bench | 11.00% | 4.33% | 2.67% | 2.00% | 5.33% | "
                                     "`torso` 13.3% | 30.00% |"));
    CHECK_THAT(page, Catch::Contains("| robot | grace | glossy | 0.5 | bench | 11.50% | 4.83% | 3.17% | 2.50% |"));
    CHECK(std::count(page.begin(), page.end(), '\n') < 20);  // two rows, not eight
}

TEST_CASE("The light-fitting table has one row per map and rule, the error at each K in its own column",
          "[bench][results-page]") {
    std::vector<json> results{{{"bench", "machine"}}};
    for (const bool cross : {true, false}) {
        results.push_back({{"bench", "lightfit"}, {"environment", "grace"}, {"cross_face", cross}, {"lights", 30},
                           {"resolution", 32}, {"merge_cost", "increase"}, {"seconds", cross ? 0.07 : 0.06}});
        results.push_back({{"bench", "lightfit"}, {"environment", "grace"}, {"cross_face", cross}, {"lights", 100},
                           {"resolution", 64}, {"merge_cost", "increase"}, {"seconds", 0.31}});
        for (const int k : {10, 30, 60, 100})
            for (const char* cost : {"merged", "increase"})
                results.push_back({{"bench", "lightfit"}, {"environment", "grace"}, {"cross_face", cross},
                                   {"lights", k}, {"resolution", 32}, {"merge_cost", cost},
                                   {"relative_l2", (cost[0] == 'm' ? 0.5 : 1.0) / k + (cross ? 0.0 : 0.01)}});
    }
    const std::string page = results_page(results, {"c", "x", "m", "d", false}, ".");
    INFO(page);
    // The rule rsl uses (increase) only: 1/10 = 10%, 1/30 = 3.33%, ...
    CHECK_THAT(page, Catch::Contains("| grace | true | 0.07 | 0.31 | 10.00% | 3.33% | 1.67% | 1.00% |"));
    CHECK_THAT(page, Catch::Contains("| grace | false | 0.06 | 0.31 | 11.00% | 4.33% | 2.67% | 2.00% |"));
    CHECK_THAT(page, !Catch::Contains("5.00%"));  // a merged-error row
}

TEST_CASE("A run's machine line names where and how it ran, for a page written later", "[bench][results-page]") {
    const json line = machine_line(true, {"render", "scale"}, {8, 128}, {16.0f, 2.5f});
    CHECK(line["bench"] == "machine");
    CHECK_THAT(line["machine"].get<std::string>(), Catch::Contains("hardware threads"));
    CHECK(line["date"].get<std::string>().size() == 10);
    const ResultsRun run = results_run({{{"bench", "render"}}, line}, "docs/RESULTS.md");
    CHECK(run.command == "rsl bench --markdown docs/RESULTS.md --quick --parts 8,128 --reaches 16,2.5 render scale");
    CHECK(run.commit == line["commit"].get<std::string>());
    CHECK(run.quick);
    // Lines without one (an older rsl's) cannot say where they were measured.
    CHECK_THROWS_WITH(results_run({{{"bench", "machine"}, {"hardware_threads", 2}}}, "x.md"),
                      Catch::Contains("no machine line naming the commit"));
}

TEST_CASE("The machine is named by its CPU and threads", "[bench][results-page]") {
    const std::string machine = describe_machine();
    CHECK_THAT(machine, Catch::Contains("hardware threads"));
    CHECK_THAT(machine, Catch::Contains("Linux"));
}

}  // namespace
}  // namespace rsl::bench
