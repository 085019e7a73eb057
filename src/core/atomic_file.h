#pragma once
// Every output goes through a temporary file beside the target and a rename, so
// an interrupted or failed write never leaves a half-written file behind.
//
// Temporaries are named ".STEM.tmp-HOST-PID-RANDOM.EXT": HOST tags this
// machine's boot and PID namespace, so that writers in separate containers or
// on separate machines (all of them PID 1, say) never share a name, and a
// sweeper judges a writer's PID only where it means the same process.
#include <chrono>
#include <filesystem>
#include <functional>
#include <string_view>

namespace rsl {

// A temporary this old is an orphan whatever wrote it: a writer holds one
// only while it writes one file, seconds, and a sweeper cannot see whether a
// writer on another machine or in another container still runs.
inline constexpr std::chrono::hours kOrphanedTemporaryAge{24};

// Calls write(tmp_path) and renames tmp_path to `path` only if write returns
// normally; on an exception the temporary file is removed and the error
// propagates. write() must check every write and the close of its file and
// throw on failure (write_file_atomically does; prefer it). Creates the
// parent directory if needed, and first sweeps the folder's orphaned
// temporaries (remove_stale_temporaries). Failures throw rsl::Error naming
// `path` and the system's reason.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp_path)>& write);

// Writes in-memory contents (JSON, images encoded in memory, binary blobs)
// through write_atomically, checking every write and the close.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Removes the orphaned temporaries in the folder of `path` (of any target):
// those of a writer of this host and PID namespace that no longer runs, and
// any older than kOrphanedTemporaryAge. The temporaries of earlier rsl
// versions (".STEM.tmp-PID-N.EXT") are judged by age alone.
void remove_stale_temporaries(const std::filesystem::path& path);

// A fresh temporary name for `path` as process `pid` of this host writes it.
std::filesystem::path temporary_path(const std::filesystem::path& path, long pid);

// Reads a whole file, or throws rsl::Error naming it.
std::string read_file(const std::filesystem::path& path);

}  // namespace rsl
