// `rsl version` (and `rsl --version`, main.cpp): the version, the commit and
// build type, the Embree and OpenEXR libraries, the renderer backends.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include "src/backend/make_renderer.h"
#include "tools/rsl/command.h"
#include "src/version/build_info.h"

namespace rsl::cli {

std::string version_text() {
    return build_info_text() + fmt::format("backends: {}\n", fmt::join(available_backends(), ", "));
}

namespace {
RegisterCommand version_command({"version", "Print the version, commit, build type and library versions of rsl",
                                 1000, [](CLI::App& app) {
                                     app.callback([] { fmt::print("{}", version_text()); });
                                 }});
}
}  // namespace rsl::cli
