#pragma once
// What this build of rsl is: `rsl --version`, `rsl version` and the public
// API's build_info() print the same lines.
#include <string>

namespace rsl {

// From the generated build_info_values.cpp (cmake/build_info.cmake).
const char* build_commit();  // `git describe --always --dirty` of the source tree, or "unknown"
const char* build_type();    // CMAKE_BUILD_TYPE

struct BuildInfo {
    std::string version;           // "0.1"
    std::string commit, build_type;
    std::string embree, openexr;   // "3.13.5 (built against 3.13.5)"
};
BuildInfo build_info();
// The lines `rsl --version` prints.
std::string build_info_text();

}  // namespace rsl
