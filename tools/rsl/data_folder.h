#pragma once
// Where `rsl demo` and `rsl bench` find the project's files (demos/,
// assets/generated, assets/scenes): beside an installed rsl
// (<prefix>/share/rsl for <prefix>/bin/rsl, cmake/install.cmake), else the
// source tree the program was built from.
#include <filesystem>

namespace rsl::cli {

std::filesystem::path data_folder();

}  // namespace rsl::cli
