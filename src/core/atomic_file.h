#pragma once
// Every output goes through a temporary file beside the target and a rename, so
// an interrupted or failed write never leaves a half-written file behind.
#include <filesystem>
#include <functional>
#include <string_view>

namespace rsl {

// Calls write(tmp_path) and renames tmp_path to `path` only if write returns
// normally; on an exception the temporary file is removed and the error
// propagates. Creates the parent directory if needed. First removes the
// temporaries of `path` that killed processes left (remove_stale_temporaries).
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp_path)>& write);

// Removes the temporary files of `path` (".STEM.tmp-PID-N.EXT" beside it)
// whose writing process no longer runs on this machine. (A process on another
// machine writing to the same shared folder would look dead: don't share an
// output folder between machines while both write.)
void remove_stale_temporaries(const std::filesystem::path& path);

// Convenience for in-memory contents (JSON, binary blobs).
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Reads a whole file, or throws rsl::Error naming it.
std::string read_file(const std::filesystem::path& path);

}  // namespace rsl
