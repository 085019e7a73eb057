#pragma once
// Reading a user's file without trusting it: only regular files (a FIFO
// would block the reader forever, a device such as /dev/zero never ends),
// the magic number checked before the rest is read, and every read bounded
// by what its format allows, so that a hostile path costs a stat, not the
// machine's memory (issue 43).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace rsl {

inline constexpr uint64_t kMiB = uint64_t(1) << 20;
inline constexpr uint64_t kGiB = uint64_t(1) << 30;

// The largest file each reader reads; a larger one is refused, with its size
// and the limit, before it is read.
// Scene files, light files and results are kilobytes to a few megabytes.
inline constexpr uint64_t kMaxJsonFileBytes = 64 * kMiB;
// About 50 million triangles of text, past what a part's fields are baked for.
inline constexpr uint64_t kMaxObjFileBytes = 4 * kGiB;
// A flat Radiance file of kMaxImagePixels (2^28, 4 bytes each) and its header.
inline constexpr uint64_t kMaxRadianceFileBytes = 4 * (uint64_t(1) << 28) + kMiB;
// A .gltf, .glb or .bin buffer: tinygltf holds the whole file in memory.
inline constexpr uint64_t kMaxGltfFileBytes = 2 * kGiB;
// An SVDF of a 50-million-vertex part at the default settings stays below this.
inline constexpr uint64_t kMaxFieldFileBytes = 4 * kGiB;
// 24 bytes a vertex (diffuse and specular): 100 million vertices stay below this.
inline constexpr uint64_t kMaxVertexColorsFileBytes = 4 * kGiB;

// Why `path` is not a regular file that can be read, in words for an error
// ("does not exist", "is a FIFO (named pipe), not a regular file"); empty
// when it is one (symbolic links followed).
std::string why_not_regular_file(const std::filesystem::path& path);

// Throws rsl::Error naming `path` unless it is a regular file (symbolic
// links followed), saying what it is instead.
void check_regular_file(const std::filesystem::path& path);

// Called on each piece of a file as it is read (e.g. to refuse NUL bytes in
// a text file before the rest is read); may throw.
using PieceCheck = std::function<void(std::string_view piece, uint64_t offset)>;

// Reads a whole regular file of at most `max_bytes`, or throws rsl::Error
// naming it: a larger file is refused with its size and the limit (`what`
// names the format: "a scene file"). When `magic` is not empty the file must
// begin with it, checked first; `not_magic` is the refusal. Opens with
// O_NONBLOCK and checks the open file again, so a FIFO swapped in after the
// first check cannot block the read.
std::string read_bounded_file(const std::filesystem::path& path, uint64_t max_bytes, std::string_view what,
                              std::string_view magic = {}, std::string_view not_magic = {},
                              const PieceCheck& check_piece = {});

// The longest value from a user's file that a message quotes.
inline constexpr size_t kMaxEchoedBytes = 80;

// A value from a user's file (a name, a URI) as a message may quote it: a
// data: URI as "a data: URI of N bytes" (its payload is the user's data, not
// a name), anything longer than kMaxEchoedBytes cut short with its length.
std::string echo_value(std::string_view value);
// A message from a library (tinygltf) with each value in it passed through
// echo_value: every data: URI, and every run of non-space bytes past kMaxEchoedBytes.
std::string echo_message(std::string_view message);

// The first `count` bytes of a regular file (fewer when it is shorter).
std::string read_file_prefix(const std::filesystem::path& path, size_t count);

}  // namespace rsl
