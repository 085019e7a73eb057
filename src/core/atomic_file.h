#pragma once
// Every output goes through a temporary file beside the target and a rename, so
// an interrupted or failed write never leaves a half-written file behind.
#include <filesystem>
#include <functional>
#include <string_view>

namespace rsl {

// Calls write(tmp_path) and renames tmp_path to `path` only if write returns
// normally; on an exception the temporary file is removed and the error
// propagates. Creates the parent directory if needed.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp_path)>& write);

// Convenience for in-memory contents (JSON, binary blobs).
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Reads a whole file, or throws rsl::Error naming it.
std::string read_file(const std::filesystem::path& path);

}  // namespace rsl
