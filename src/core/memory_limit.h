#pragma once
// One memory limit for the program, the C++ API and the Python module: work
// whose estimated peak memory passes it is refused before anything large is
// allocated, naming the file and the way out (docs/SCENE_FORMAT.md, "Memory").
#include <cstdint>
#include <filesystem>
#include <string>

namespace rsl {

// The limit in bytes; 0 means none. By default 80% of the machine's memory
// (the smallest of MemTotal, the cgroup's memory.max and `ulimit -v`), or the environment
// variable RSL_MEMORY_LIMIT when it is set (a size such as 8G or 512M, or
// "none"); set_memory_limit overrides both.
uint64_t memory_limit();
void set_memory_limit(uint64_t bytes);
uint64_t default_memory_limit();

// "8G", "512M", "64K", "1.5G", a byte count, or "none"/"0" (no limit) →
// bytes; throws rsl::Error naming `what` (the flag or variable) otherwise.
uint64_t parse_memory_size(const std::string& text, const std::string& what);

// "1.2 GB"-style text for messages.
std::string memory_size_text(uint64_t bytes);

// An image a run forms, and its tone-mapped PNG's luminance, bytes and
// encoder (measured: 31 bytes a pixel for `rsl render` of a 4096² view its
// parts cover, 24 for `rsl truth`).
inline constexpr uint64_t kImageBytesPerPixel = 32;
uint64_t image_memory_bytes(int width, int height);

// How the caller sets the limit, named in the refusal's way out: the C++
// API's "rsl::api::set_memory_limit" unless the front end says otherwise
// when it starts (the program: "--memory-limit"; Python:
// "rsl.set_memory_limit"). `name` must outlive every refusal: a literal.
void set_memory_limit_setter(const char* name);

// Throws rsl::Error naming `file` when `estimate_bytes` passes the limit;
// `what` says what needs the memory ("2,890,000 vertices in 10,000 parts").
void check_memory_estimate(uint64_t estimate_bytes, const std::filesystem::path& file, const std::string& what);

}  // namespace rsl
