#pragma once
// Subcommands register themselves: each cmd_*.cpp defines one static
// RegisterCommand, and main() builds the CLI11 app from the registry.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace rsl::cli {

struct Command {
    std::string name;
    std::string description;
    int order = 100;  // position in `rsl --help`
    // Adds the options to `app` and sets its callback; the callback throws
    // rsl::Error on failure.
    std::function<void(CLI::App& app)> setup;
};

std::vector<Command>& command_registry();

// What `rsl --version` and `rsl version` print (cmd_version.cpp).
std::string version_text();

struct RegisterCommand {
    explicit RegisterCommand(Command command) { command_registry().push_back(std::move(command)); }
};

}  // namespace rsl::cli
