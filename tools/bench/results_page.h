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

// The page for the result lines of one run (bench_results()), in the order
// of the sections below; a benchmark without a section of its own gets a
// table of its numeric figures. Plots the run wrote (a "plot" line) are
// linked by their path relative to `page_folder`.
std::string results_page(const std::vector<nlohmann::json>& results, const ResultsRun& run,
                         const std::filesystem::path& page_folder);

}  // namespace rsl::bench
