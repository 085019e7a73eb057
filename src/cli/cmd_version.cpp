#include <fmt/core.h>

#include "src/cli/command.h"

namespace rsl::cli {
namespace {
RegisterCommand version_command({"version", "Print the version of rsl", 1000, [](CLI::App& app) {
                                     app.callback([] { fmt::print("rsl 0.1\n"); });
                                 }});
}
}  // namespace rsl::cli
