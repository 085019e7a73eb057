#include "tools/bench/results_page.h"

#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <map>
#include <functional>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "src/core/error.h"
#include "src/version/build_info.h"

namespace rsl::bench {

namespace {

using nlohmann::json;

enum class Format { Text, Count, Percent, Milliseconds, SecondsAsMs, Seconds, Ratio, Scientific, Megabytes, Decimal };

struct Column {
    std::string key, header;
    Format format;
};

// One benchmark's table: which of its lines (`keep`), and which figures.
struct Section {
    std::string bench, title, text;
    std::vector<Column> columns;
    std::function<bool(const json&)> keep = [](const json&) { return true; };
    // Rows merged before the table is written (the accuracy's K in columns); none: as they come.
    std::function<std::vector<json>(const std::vector<json>&)> combine = nullptr;
};

std::string with_thousands(long long value) {
    const std::string digits = std::to_string(value < 0 ? -value : value);
    std::string out(value < 0 ? 1 : 0, '-');
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out.push_back(',');
        out.push_back(digits[i]);
    }
    return out;
}

std::string cell(const json& row, const Column& column) {
    if (!row.contains(column.key) || row[column.key].is_null()) return "";
    const json& v = row[column.key];
    if (!v.is_number()) return v.is_string() ? v.get<std::string>() : v.dump();
    const double x = v.get<double>();
    switch (column.format) {
    case Format::Count: return with_thousands(std::llround(x));
    case Format::Percent: return fmt::format("{:.2f}%", 100.0 * x);
    case Format::Milliseconds: return fmt::format("{:.1f}", x);
    case Format::SecondsAsMs: return fmt::format("{:.1f}", 1e3 * x);
    case Format::Seconds: return fmt::format("{:.2f}", x);
    case Format::Ratio: return fmt::format("{:.1f}×", x);
    case Format::Scientific: return fmt::format("{:.1e}", x);
    case Format::Megabytes: return fmt::format("{:.1f}", x / 1e6);
    case Format::Decimal:  // three significant digits, never in exponent form
        return std::abs(x) >= 100 ? fmt::format("{:.0f}", x)
                                  : std::abs(x) >= 10 ? fmt::format("{:.1f}", x) : fmt::format("{:.3g}", x);
    case Format::Text: return v.dump();
    }
    return v.dump();
}

// "upper_arm_l 9.5%": a part's name and its error in one cell.
void add_worst_part(json& row, const std::string& error_key) {
    if (row.contains("worst_part") && row.contains(error_key) && row[error_key].is_number())
        row["worst_part_cell"] = fmt::format("`{}` {:.1f}%", row["worst_part"].get<std::string>(),
                                             100.0 * row[error_key].get<double>());
}

// Rows with the same values of `group` merged into one, in the order first
// seen: the group's values, then what `spread` takes from each row.
std::vector<json> merge_rows(const std::vector<json>& rows, const std::vector<std::string>& group,
                             const std::function<void(const json& row, json& merged)>& spread) {
    std::vector<json> merged;
    std::map<std::string, size_t> index;
    for (const json& row : rows) {
        json key = json::array();
        for (const std::string& k : group) key.push_back(row.contains(k) ? row[k] : json());
        auto [at, added] = index.emplace(key.dump(), merged.size());
        if (added) {
            json first{{"bench", row.value("bench", "")}};
            for (const std::string& k : group)
                if (row.contains(k)) first[k] = row[k];
            merged.push_back(std::move(first));
        }
        spread(row, merged[at->second]);
    }
    return merged;
}

// Accuracy: one row per frame, the error at each K in its own column and the rest at K = 30.
std::vector<json> accuracy_by_lights(const std::vector<json>& rows) {
    return merge_rows(rows, {"scene", "environment", "material", "time", "precompute"}, [](const json& row, json& m) {
        const int lights = row.value("lights", 0);
        if (row.contains("relative_l2")) m[fmt::format("relative_l2_k{}", lights)] = row["relative_l2"];
        if (lights == 30)
            for (auto it = row.begin(); it != row.end(); ++it)
                if (!m.contains(it.key()) && it.key() != "lights") m[it.key()] = it.value();
    });
}

// Light fitting: one row per map and rule, its times and its error at each K.
std::vector<json> lightfit_by_lights(const std::vector<json>& rows) {
    return merge_rows(rows, {"environment", "cross_face"}, [](const json& row, json& m) {
        const int lights = row.value("lights", 0);
        if (row.contains("seconds")) m[fmt::format("seconds_{}_k{}", row.value("resolution", 0), lights)] = row["seconds"];
        if (row.contains("relative_l2")) m[fmt::format("relative_l2_k{}", lights)] = row["relative_l2"];
    });
}

// Error budget: one row per frame and K, each variant's error (all vertices /
// objects) in its own column.
std::vector<json> budget_by_variant(const std::vector<json>& rows) {
    return merge_rows(rows, {"scene", "environment", "time", "lights", "precompute"}, [](const json& row, json& m) {
        const std::string variant = row.value("variant", "");
        if (!row.contains("relative_l2") || !row.contains("objects_relative_l2")) return;
        m["budget_" + variant] = fmt::format("{:.2f}% / {:.2f}%", 100.0 * row["relative_l2"].get<double>(),
                                             100.0 * row["objects_relative_l2"].get<double>());
        if (variant == "renderer" && row.contains("worst_part_cell")) m["worst_part_cell"] = row["worst_part_cell"];
    });
}

std::vector<Section> sections() {
    const Column worst{"worst_part_cell", "worst part", Format::Text};
    return {
        {"render", "Shading on the CPU",
         "`rsl bench render`: one frame of each scene at K = 30, the bench field settings (SVDF 16², 13 OVDF "
         "shells), all cores, the median of five. *Image* is `rsl render`'s image with per-pixel shadows and "
         "highlights at the size given; *truth* is the same frame's Embree ground truth, and the speed-up is "
         "its time over the shading's.",
         {{"case", "scene", Format::Text},
          {"vertices", "vertices", Format::Count},
          {"lights", "K", Format::Count},
          {"shade_seconds", "shading ms", Format::SecondsAsMs},
          {"fps_shading", "fps", Format::Decimal},
          {"image", "image", Format::Text},
          {"image_seconds_per_pixel", "image ms", Format::SecondsAsMs},
          {"relative_l2_vs_truth", "error: all", Format::Percent},
          {"objects_relative_l2_vs_truth", "objects", Format::Percent},
          worst,
          {"truth_seconds", "truth s", Format::Seconds},
          {"speedup_shading", "speed-up", Format::Ratio}}},
        {"render-accuracy", "Accuracy",
         "`rsl bench render-accuracy` and `rsl bench render-goal`: the renderer against the ground truth of the "
         "same frame, per vertex. *Fields* says whose precomputation settings: the bench's (small, baked in "
         "seconds) or the scene file's own. *Without OVDF* is the error with the other parts' shadows left out: "
         "what the occluder fields bring. The objects, the worst part and *without OVDF* are at K = 30.",
         {{"scene", "scene", Format::Text},
          {"environment", "environment", Format::Text},
          {"material", "material", Format::Text},
          {"time", "t", Format::Decimal},
          {"precompute", "fields", Format::Text},
          {"relative_l2_k10", "all, K = 10", Format::Percent},
          {"relative_l2_k30", "all, K = 30", Format::Percent},
          {"relative_l2_k60", "all, K = 60", Format::Percent},
          {"relative_l2_k100", "all, K = 100", Format::Percent},
          {"objects_relative_l2", "objects, K = 30", Format::Percent},
          worst,
          {"relative_l2_without_occluders", "without OVDF", Format::Percent}},
         [](const json&) { return true; }, accuracy_by_lights},
        {"render-factors", "Error budget",
         "`rsl bench render-factors`: where the renderer's error comes from. Each column is the error against the "
         "ground truth, all vertices / the objects, with one approximation replaced by its exact value: "
         "*unshadowed* is the light alone (the squares and the BRDF tables, every visibility factor off, against the "
         "unshadowed truth), split into the *tables* (the truth's unshadowed integral with ρ·cos read from the BRDF "
         "tables) and the *squares* (the unshadowed renderer against that); *exact self*, "
         "*exact others* and *exact visibility* trace rays over each square (8×8 per square) in place of the SVDF, "
         "the OVDFs or both; *exact light* multiplies the exact unshadowed integral by the renderer's own ratio of "
         "shadowed to unshadowed light (the visibility's error alone). The scene files' field settings; local "
         "lights off.",
         {{"scene", "scene", Format::Text},
          {"environment", "environment", Format::Text},
          {"time", "t", Format::Decimal},
          {"lights", "K", Format::Count},
          {"budget_renderer", "renderer", Format::Text},
          worst,
          {"budget_unshadowed", "unshadowed", Format::Text},
          {"budget_tables", "tables", Format::Text},
          {"budget_squares", "squares", Format::Text},
          {"budget_exact_self", "exact self", Format::Text},
          {"budget_exact_others", "exact others", Format::Text},
          {"budget_exact_visibility", "exact visibility", Format::Text},
          {"budget_ratio_oracle", "exact light", Format::Text}},
         [](const json& row) { return row.contains("variant"); }, budget_by_variant},
        {"scale", "Many moving parts",
         "`rsl bench scale`: yard-N, N instances of four small meshes bouncing, tumbling and orbiting on a ground "
         "(`rsl assets --yard N`), K = 30, the median of five frames; the errors are the means over them (the "
         "truth runs for N ≤ 64). Every N shares the same few field files.",
         {{"instances", "N", Format::Count},
          {"vertices", "vertices", Format::Count},
          {"shade_ms", "shading ms", Format::Milliseconds},
          {"fps_shading", "fps", Format::Decimal},
          {"ns_per_vertex", "ns per vertex", Format::Decimal},
          {"ovdf_lookups_per_frame", "OVDF lookups", Format::Count},
          {"field_ram_bytes", "field MB", Format::Megabytes},
          {"relative_l2_vs_truth", "error: all", Format::Percent},
          {"objects_relative_l2", "objects", Format::Percent},
          worst},
         [](const json& row) { return row.contains("instances"); }},
        {"gl", "The GPU renderer against the CPU renderer",
         "`rsl bench gl`: the same frames shaded by the GL compute pass and by the CPU renderer in one run, "
         "alternated, the least time of each. *Lookups* are OVDF lookups per frame; *parity* is the relative L2 "
         "between the two backends' vertex colours; *frame* adds the display and per-pixel passes at 640×480. "
         "On Mesa llvmpipe (a software rasterizer) the GPU figures measure the shader's work on the CPU's own "
         "cores, not a GPU's speed ([GPU.md](GPU.md)).",
         {{"case", "scene", Format::Text},
          {"vertices", "vertices", Format::Count},
          {"cpu_shading_ms", "CPU ms", Format::Milliseconds},
          {"gpu_shading_ms", "GPU ms", Format::Milliseconds},
          {"gpu_over_cpu", "GPU / CPU", Format::Ratio},
          {"cpu_occluder_lookups", "CPU lookups", Format::Count},
          {"gpu_occluder_lookups", "GPU lookups", Format::Count},
          {"gpu_cpu_relative_l2", "parity", Format::Scientific},
          {"frame_ms", "frame ms", Format::Milliseconds}},
         [](const json& row) { return row.contains("gpu_over_cpu"); }},
        {"lightfit", "Fitting the lights",
         "`rsl bench lightfit`: the environment map's decomposition into K rotatable square lights, with the merge "
         "rule rsl uses (the least increase of error): its time on a 6×32² and a 6×64² cube map, and the relative "
         "L2 of the lights' reconstruction of the 6×32² map at each K. *Across faces*: regions may span cube faces "
         "(the default; the paper's rule keeps each within one face, `--same-face`).",
         {{"environment", "map", Format::Text},
          {"cross_face", "across faces", Format::Text},
          {"seconds_32_k30", "s, 6×32² → 30", Format::Seconds},
          {"seconds_64_k100", "s, 6×64² → 100", Format::Seconds},
          {"relative_l2_k10", "error, K = 10", Format::Percent},
          {"relative_l2_k30", "K = 30", Format::Percent},
          {"relative_l2_k60", "K = 60", Format::Percent},
          {"relative_l2_k100", "K = 100", Format::Percent}},
         [](const json& row) { return row.value("merge_cost", "increase") == "increase"; }, lightfit_by_lights},
        {"truth", "The ground truth",
         "`rsl bench truth`: the Embree truth every error on this page is measured against.",
         {{"case", "case", Format::Text},
          {"vertices", "vertices", Format::Count},
          {"seconds", "seconds", Format::Seconds},
          {"shadow_rays_per_second", "shadow rays per second", Format::Count}}},
    };
}

// A table of a benchmark without a section: its case and numeric figures.
Section generic_section(const std::string& bench, const std::vector<json>& rows) {
    Section s{bench, fmt::format("`rsl bench {}`", bench), "", {{"case", "case", Format::Text}}};
    std::set<std::string> seen{"bench", "case"};
    for (const json& row : rows)
        for (auto it = row.begin(); it != row.end() && s.columns.size() < 8; ++it)
            if (it.value().is_number() && seen.insert(it.key()).second)
                s.columns.push_back({it.key(), it.key(), Format::Decimal});
    return s;
}

void write_table(std::string& page, const Section& section, const std::vector<json>& rows) {
    std::vector<Column> columns;
    for (const Column& c : section.columns)  // a column no row fills is left out
        if (std::any_of(rows.begin(), rows.end(), [&](const json& r) { return !cell(r, c).empty(); }))
            columns.push_back(c);
    std::string header = "|", rule = "|";
    for (const Column& c : columns) {
        header.append(" ").append(c.header).append(" |");
        rule.append(c.format == Format::Text ? " --- |" : " ---: |");
    }
    page.append(header).append("\n").append(rule).append("\n");
    for (const json& row : rows) {
        page.append("|");
        for (const Column& c : columns) page.append(" ").append(cell(row, c)).append(" |");
        page.append("\n");
    }
}

std::string relative_path(const std::filesystem::path& path, const std::filesystem::path& folder) {
    std::error_code ec;
    const std::filesystem::path relative = std::filesystem::relative(path, folder, ec);
    return ec || relative.empty() ? path.string() : relative.generic_string();
}

void write_section(std::string& page, const Section& section, const std::vector<json>& lines,
                   const std::filesystem::path& page_folder) {
    std::vector<json> rows;
    std::vector<std::string> skipped, plots;
    for (json row : lines) {
        if (row.contains("skipped")) {
            skipped.push_back(fmt::format("{}: {}", row.value("case", section.bench), row["skipped"].get<std::string>()));
        } else if (row.contains("plot")) {
            plots.push_back(relative_path(row["plot"].get<std::string>(), page_folder));
        } else if (section.keep(row)) {
            add_worst_part(row, row.contains("worst_part_relative_l2_vs_truth") ? "worst_part_relative_l2_vs_truth"
                                                                               : "worst_part_relative_l2");
            rows.push_back(std::move(row));
        }
    }
    if (section.combine) rows = section.combine(rows);
    if (rows.empty() && skipped.empty() && plots.empty()) return;
    page += "\n## " + section.title + "\n\n";
    if (!section.text.empty()) page += section.text + "\n\n";
    if (!rows.empty()) write_table(page, section, rows);
    for (const std::string& plot : plots) page += fmt::format("\n![{}]({})\n", section.title, plot);
    for (const std::string& s : skipped) page += "\n- skipped: " + s;
    if (!skipped.empty()) page += "\n";
}

std::string first_line_of(const std::filesystem::path& file, const std::string& prefix) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) {
            const size_t colon = line.find(':');
            if (colon == std::string::npos) return "";
            const size_t start = line.find_first_not_of(" \t", colon + 1);
            return start == std::string::npos ? "" : line.substr(start);
        }
    return "";
}

}  // namespace

std::string describe_machine() {
    std::string cpu = first_line_of("/proc/cpuinfo", "model name");
    if (cpu.empty()) cpu = "an unknown CPU";
    std::string text = fmt::format("{}, {} hardware threads", cpu, std::thread::hardware_concurrency());
    utsname name{};
    if (uname(&name) == 0) text += fmt::format(", {} {}", name.sysname, name.release);
    return text;
}

json machine_line(bool quick, const std::vector<std::string>& names, const std::vector<int>& parts,
                  const std::vector<float>& reaches) {
    const std::time_t now = std::time(nullptr);
    char date[16];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    return {{"bench", "machine"}, {"hardware_threads", std::thread::hardware_concurrency()},
            {"quick", quick},     {"machine", describe_machine()},
            {"commit", build_commit()}, {"date", date},
            {"names", names},     {"parts", parts},
            {"reaches", reaches}};
}

ResultsRun results_run(const std::vector<json>& results, const std::string& page) {
    const auto line = std::find_if(results.begin(), results.end(),
                                   [](const json& row) { return row.value("bench", "") == "machine"; });
    if (line == results.end() || !line->contains("commit") || !line->contains("machine") || !line->contains("date"))
        throw_error("the results have no machine line naming the commit, machine and date (written by an older rsl "
                    "bench?): the page could not say where they were measured");
    const json& m = *line;
    ResultsRun run{"rsl bench --markdown " + page, m["commit"].get<std::string>(), m["machine"].get<std::string>(),
                   m["date"].get<std::string>(), m.value("quick", false)};
    if (run.quick) run.command += " --quick";
    if (const auto parts = m.value("parts", std::vector<int>{}); !parts.empty())
        run.command += fmt::format(" --parts {}", fmt::join(parts, ","));
    if (const auto reaches = m.value("reaches", std::vector<float>{}); !reaches.empty())
        run.command += fmt::format(" --reaches {:g}", fmt::join(reaches, ","));
    for (const std::string& name : m.value("names", std::vector<std::string>{})) run.command += " " + name;
    return run;
}

std::string results_page(const std::vector<json>& results, const ResultsRun& run,
                         const std::filesystem::path& page_folder) {
    std::string device;
    for (const json& row : results)
        if (row.contains("device") && row["device"].is_string()) device = row["device"].get<std::string>();
    std::string page = "# Results: how accurate and how fast\n\n";
    page += fmt::format(
        "Written by `{}` at commit `{}` on {}, on {}{}. Run the command again to bring the page up to date; "
        "do not edit it by hand. Times on a shared machine move by 10–20% from run to run; errors do not.{}\n\n",
        run.command, run.commit, run.date, run.machine, device.empty() ? "" : "; OpenGL: " + device,
        run.quick ? " **These are `--quick` figures: smaller cases, for checking the page, not for quoting.**" : "");
    page +=
        "**Error** is relative L2 over RGB, ‖A − B‖₂ / ‖B‖₂, against the Embree ground truth of the same frame "
        "(`rsl truth`: every cube-map texel with a shadow ray): over all vertices, over the *objects* (every part "
        "but the ground or floor), and for the *worst part* ([design/TRUTH.md](design/TRUTH.md), \"Errors\"). "
        "K is the number of rotatable square lights. How RSL compares with other methods (ray-traced shadows, "
        "shadow maps, SH and Haar PRT) is in [BASELINES.md](BASELINES.md); the demos' frame times are in "
        "[DEMOS.md](DEMOS.md).\n";

    std::vector<Section> known = sections();
    std::vector<std::string> order;
    for (const json& row : results) {
        const std::string bench = row.value("bench", "");
        if (bench.empty() || bench == "machine") continue;
        if (std::find(order.begin(), order.end(), bench) == order.end()) order.push_back(bench);
    }
    auto lines_of = [&](const std::string& bench) {
        std::vector<json> lines;
        for (const json& row : results)
            if (row.value("bench", "") == bench) lines.push_back(row);
        return lines;
    };
    for (const Section& section : known)  // the sections' own order first
        if (std::find(order.begin(), order.end(), section.bench) != order.end())
            write_section(page, section, lines_of(section.bench), page_folder);
    for (const std::string& bench : order)
        if (std::none_of(known.begin(), known.end(), [&](const Section& s) { return s.bench == bench; }))
            write_section(page, generic_section(bench, lines_of(bench)), lines_of(bench), page_folder);
    return page;
}

}  // namespace rsl::bench
