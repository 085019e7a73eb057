#pragma once
// docs/RESULTS.md is written by `rsl bench --markdown FILE NAMES...`, not by
// hand: one page of the figures of that run, with the machine, the commit
// and the command named, so that every figure can be measured again.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rsl::bench {

// Where and how the page's figures were measured.
struct ResultsRun {
    std::string command;  // the command line that wrote the page
    std::string commit;   // build_commit()
    std::string machine;  // describe_machine()
    std::string date;     // UTC, YYYY-MM-DD
    bool quick = false;   // --quick: smaller cases
};

// "Intel(R) Xeon(R) ... , 2 hardware threads, Linux 6.1.0": the CPU model,
// the threads and the kernel of this machine.
std::string describe_machine();

// A run's first line ("bench": "machine"): this machine, the commit, today's
// date and the run's arguments, so that a page written later from saved
// lines (`rsl bench --markdown PAGE --from-json FILE`) names the run's own.
nlohmann::json machine_line(bool quick, const std::vector<std::string>& names, const std::vector<int>& parts,
                            const std::vector<float>& reaches);

// The run described by the machine line of `results`, with the command line
// that writes `page` again; refuses lines without one (a run of an older rsl).
ResultsRun results_run(const std::vector<nlohmann::json>& results, const std::string& page);

// The page for the result lines of one run (bench_results()), in the order
// of the sections below; a benchmark without a section of its own gets a
// table of its numeric figures. Plots the run wrote (a "plot" line) are
// linked by their path relative to `page_folder`.
std::string results_page(const std::vector<nlohmann::json>& results, const ResultsRun& run,
                         const std::filesystem::path& page_folder);

}  // namespace rsl::bench
