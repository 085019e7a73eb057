// `rsl bench [NAMES...]`: run registered benchmarks, JSON lines on stdout;
// with --markdown also the page of their figures (tools/bench/results_page.h).
#include <algorithm>
#include <filesystem>
#include <sstream>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "tools/assets/yard.h"
#include "tools/bench/bench.h"
#include "tools/bench/results_page.h"
#include "tools/rsl/command.h"
#include "tools/rsl/data_folder.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"

namespace rsl::cli {

// The benchmarks and their registry live in bench/ (library rsl_bench).
using bench::BenchOptions;
using bench::Benchmark;
using bench::bench_emit;
using bench::bench_results;
using bench::benchmark_registry;

namespace {
struct BenchArgs {
    std::vector<std::string> names;
    bool quick = false;
    bool list = false;
    std::string json_out;
    std::string markdown;
    std::string from_json;
    std::string shared = std::string(RSL_SOURCE_DIR) + "/../shared/assets";
    std::string generated = (data_folder() / "assets" / "generated").string();
    std::string scenes = (data_folder() / "assets" / "scenes").string();
    std::string output = "bench-out";
    std::string cache;  // empty: OUT/.rsl-cache
    std::vector<int> parts;
    std::vector<float> reaches;
};

// The results of a saved run: the JSON array of --json-out, or the JSON
// lines a run prints on stdout.
std::vector<nlohmann::json> read_saved_results(const std::string& file) {
    const std::string text = read_bounded_file(file, kMaxJsonFileBytes, "a results file");
    std::vector<nlohmann::json> lines;
    try {
        if (const size_t first = text.find_first_not_of(" \t\r\n"); first != std::string::npos && text[first] == '[') {
            lines = nlohmann::json::parse(text).get<std::vector<nlohmann::json>>();
        } else {
            std::istringstream in(text);
            for (std::string line; std::getline(in, line);)
                if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(nlohmann::json::parse(line));
        }
    } catch (const nlohmann::json::exception& e) {
        throw_error("{}: not the results of rsl bench (a JSON array or JSON lines): {}", file, e.what());
    }
    for (size_t i = 0; i < lines.size(); ++i)
        if (!lines[i].is_object())
            throw_error("{}: result {} is {}, not an object as rsl bench writes", file, i + 1, lines[i].type_name());
    return lines;
}

// The page of a run's results; the plots it links are copied beside it
// (gallery/), since the --out folder is scratch.
void write_markdown(const std::string& page_path, std::vector<nlohmann::json> results) {
    namespace fs = std::filesystem;
    const fs::path page = page_path;
    const fs::path folder = page.has_parent_path() ? page.parent_path() : fs::path(".");
    const bench::ResultsRun run = bench::results_run(results, page_path);  // before anything is written
    for (nlohmann::json& row : results) {
        if (!row.contains("plot")) continue;
        const fs::path plot = row["plot"].get<std::string>();
        const fs::path copy = folder / "gallery" / fmt::format("results_{}_{}", row.value("bench", "bench"),
                                                               plot.filename().string());
        // A page written again from a saved run finds the plot in its own gallery.
        std::error_code same;
        const bool held = fs::equivalent(plot, copy, same) || (!fs::exists(plot) && fs::exists(copy));
        if (!held) {
            if (!fs::exists(plot)) throw_error("the run's plot {} is gone and {} holds no copy", plot.string(), copy.string());
            write_atomically(copy, [&](const fs::path& tmp) { fs::copy_file(plot, tmp, fs::copy_options::overwrite_existing); });
        }
        row["plot"] = copy.string();
    }
    write_file_atomically(page, bench::results_page(results, run, folder));
}

RegisterCommand bench_command({"bench",
    "Run benchmarks; one JSON object per result line on stdout (timings, rates, memory, errors).",
    90, [](CLI::App& app) {
        auto args = std::make_shared<BenchArgs>();
        app.add_option("names", args->names, "Benchmarks to run (default: all); see --list");
        app.add_flag("--list", args->list, "List the benchmarks and exit");
        app.add_flag("--quick", args->quick, "Smaller cases (smoke test)");
        app.add_option("--json-out", args->json_out, "Also write all results as a JSON array to this file");
        app.add_option("--markdown", args->markdown,
                       "Also write the results as a page of tables naming the machine, the commit and this command "
                       "(docs/RESULTS.md is written so: rsl bench --markdown docs/RESULTS.md render render-accuracy "
                       "render-goal scale gl lightfit); plots are copied into its folder's gallery/");
        app.add_option("--from-json", args->from_json,
                       "With --markdown: write the page from a saved run (its --json-out, or its stdout lines) "
                       "instead of running; the page names that run's machine, commit and command");
        app.add_option("--shared-assets", args->shared, "Folder of real probes/meshes (optional)")->capture_default_str();
        app.add_option("--generated-assets", args->generated, "The project's generated assets")->capture_default_str();
        app.add_option("--scenes", args->scenes, "The project's scene files")->capture_default_str();
        app.add_option("--out", args->output, "Folder for plots, generated scenes and the field cache")->capture_default_str();
        app.add_option("--cache", args->cache, "Field cache folder for the scenes of --scenes (default: OUT/.rsl-cache)");
        app.add_option("--parts", args->parts, "scale: yard instance counts (default 8,32,64,128,256,1024)")
            ->delimiter(',')
            ->check(CLI::Range(1, 4096));
        app.add_option("--reaches", args->reaches,
                       fmt::format("scale: OVDF outer radii in bounding radii to compare (default: the yard's {:g})",
                                   assets::kYardOvdfReach))
            ->delimiter(',')
            ->check(CLI::Range(1.5, 100.0));
        app.callback([args] {
            auto& registry = benchmark_registry();
            std::sort(registry.begin(), registry.end(),
                      [](const Benchmark& a, const Benchmark& b) { return a.name < b.name; });
            if (args->list) {
                for (auto& b : registry) fmt::print("{:<16} {}\n", b.name, b.description);
                return;
            }
            if (!args->from_json.empty()) {
                if (args->markdown.empty()) throw_error("--from-json {}: give the page to write with --markdown", args->from_json);
                if (!args->names.empty()) throw_error("--from-json writes a saved run's page: name no benchmarks to run");
                check_outputs_apart({args->markdown, args->json_out}, {args->from_json});
                write_markdown(args->markdown, read_saved_results(args->from_json));
                return;
            }
            check_outputs_apart({args->markdown, args->json_out}, {});
            for (auto& name : args->names)
                if (std::none_of(registry.begin(), registry.end(), [&](auto& b) { return b.name == name; }))
                    throw_error("unknown benchmark '{}' (see rsl bench --list)", name);
            BenchOptions options{args->quick, args->shared, args->generated, args->scenes, args->output, args->parts,
                                 args->reaches,
                                 args->cache.empty() ? std::filesystem::path(args->output) / ".rsl-cache"
                                                     : std::filesystem::path(args->cache)};
            bench_emit(bench::machine_line(args->quick, args->names, args->parts, args->reaches));
            for (auto& b : registry) {
                if (!args->names.empty() &&
                    std::find(args->names.begin(), args->names.end(), b.name) == args->names.end())
                    continue;
                b.run(options);
            }
            if (!args->json_out.empty())
                write_file_atomically(args->json_out, nlohmann::json(bench_results()).dump(2));
            if (!args->markdown.empty()) write_markdown(args->markdown, bench_results());
        });
    }});
}  // namespace
}  // namespace rsl::cli
