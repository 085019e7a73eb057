#pragma once
// JSON input files (scene files, light sets): one parse whose every failure —
// bad syntax, a number out of range (1e309), a truncated file — is an
// rsl::Error naming the file, the line and column, and the key being read.
// nlohmann's own exceptions name none of these, and its range errors are not
// parse errors, so callers that caught only parse_error let them escape as
// internal errors.
#include <filesystem>
#include <string_view>

#include <nlohmann/json.hpp>

namespace rsl {

// Parses `text`, the contents of `path`.
nlohmann::json parse_json_text(const std::filesystem::path& path, std::string_view text);
// Reads and parses `path` (an unreadable file is an error naming it).
nlohmann::json read_json_file(const std::filesystem::path& path);

}  // namespace rsl
