#pragma once
// `rsl info FILE...`: prints what a file holds. Each kind of file registers a
// handler (a static RegisterInfoHandler in its own .cpp), so stages add their
// file types (field files, light sets...) without touching cmd_info.cpp.
// The first handler that accepts a file prints it; print() throws rsl::Error
// on a bad file.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rsl::cli {

struct InfoHandler {
    std::string name;  // "environment", "mesh", "scene", ...
    std::function<bool(const std::filesystem::path&)> accepts;  // usually by extension
    std::function<void(const std::filesystem::path&)> print;    // to stdout
};

std::vector<InfoHandler>& info_handler_registry();

struct RegisterInfoHandler {
    explicit RegisterInfoHandler(InfoHandler handler) { info_handler_registry().push_back(std::move(handler)); }
};

// Lower-case extension with the dot (".exr"), for `accepts`.
std::string lowercase_extension(const std::filesystem::path& path);

// Whether `path` is a light set written by `rsl fit` (a .json whose "format"
// is "rsl-lights"), not a scene file.
bool is_light_set_file(const std::filesystem::path& path);

}  // namespace rsl::cli
