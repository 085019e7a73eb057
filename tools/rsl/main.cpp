// rsl: the one command-line program. Each subcommand lives in its own cmd_*.cpp.
#include <algorithm>
#include <cstdio>
#include <exception>

#include "tools/rsl/command.h"
#include "src/core/error.h"
#include "src/core/memory_limit.h"

namespace rsl::cli {
std::vector<Command>& command_registry() {
    static std::vector<Command> registry;
    return registry;
}
}  // namespace rsl::cli

int main(int argc, char** argv) {
    using namespace rsl::cli;
    CLI::App app{
        "rsl — all-frequency environment lighting of dynamic scenes with rotatable square lights.\n"
        "Pipeline: fit (environment → RSLs), bake (visibility fields), render / view (runtime),\n"
        "truth (Embree ground truth), compare (error), bench (machine-readable numbers)."};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Print help for every subcommand");
    // The text ends in a newline; CLI11 adds one more.
    app.set_version_flag("--version", [] {
        std::string text = version_text();
        if (!text.empty() && text.back() == '\n') text.pop_back();
        return text;
    }, "Print the version, commit, build type and library versions, and exit");
    // One memory limit for every subcommand (src/core/memory_limit.h), given
    // before or after the subcommand's own arguments.
    rsl::set_memory_limit_setter("--memory-limit");
    app.add_option_function<std::string>(
           "--memory-limit", [](const std::string& text) { rsl::set_memory_limit(rsl::parse_memory_size(text, "--memory-limit")); },
           "Refuse work whose estimated memory passes SIZE (such as 8G; none or 0: no limit). Default: RSL_MEMORY_LIMIT, "
           "or 80% of this machine's memory")
        ->type_name("SIZE")
        ->trigger_on_parse();
    auto& commands = command_registry();
    std::stable_sort(commands.begin(), commands.end(),
                     [](const Command& a, const Command& b) { return a.order < b.order; });
    for (auto& command : commands) {
        CLI::App* sub = app.add_subcommand(command.name, command.description);
        command.setup(*sub);
        sub->fallthrough();
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const rsl::Error& e) {
        std::fprintf(stderr, "rsl: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rsl: internal error: %s\n", e.what());
        return 2;
    }
    return 0;
}
