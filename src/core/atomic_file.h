#pragma once
// Every output goes through a temporary file beside the target and a rename, so
// an interrupted or failed write never leaves a half-written file behind.
//
// Temporaries are named ".STEM.rsl-tmp-HOST-PID-RANDOM.EXT": HOST tags this
// machine's boot and PID namespace, so that writers in separate containers or
// on separate machines (all of them PID 1, say) never share a name, and a
// sweeper judges a writer's PID only where it means the same process. The
// sweep removes only names of exactly that shape (16 hex digits, a PID, 16 hex
// digits), so a user's own ".notes.tmp-2024-06.txt" is never taken for one.
// STEM is cut short where the name would pass NAME_MAX (255 bytes).
#include <chrono>
#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace rsl {

// What every temporary's name holds after its stem.
inline constexpr std::string_view kTemporaryMarker = ".rsl-tmp-";

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
// any older than kOrphanedTemporaryAge. Other names are never touched.
void remove_stale_temporaries(const std::filesystem::path& path);

// A fresh temporary name for `path` as process `pid` of this host writes it.
std::filesystem::path temporary_path(const std::filesystem::path& path, long pid);

// Throws rsl::Error naming both paths when an output is one of the inputs
// (the same file by any spelling, link or hard link) or two outputs are one
// file, before anything is written: `rsl fit env.exr -o env.exr` would
// otherwise replace the map it reads. Every command checks its outputs here
// against every file it reads (for a scene, Scene::input_files).
void check_outputs_apart(const std::vector<std::filesystem::path>& outputs,
                         const std::vector<std::filesystem::path>& inputs);

// Reads a whole file, or throws rsl::Error naming it.
std::string read_file(const std::filesystem::path& path);

}  // namespace rsl
