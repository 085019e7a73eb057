#pragma once
// The FNV-1a 64 hash: the checksum that rsl's binary files end with
// (src/formats/binary_io.h) and the key of in-memory and on-disk caches.
#include <cstddef>
#include <cstdint>

namespace rsl {

inline constexpr uint64_t kFnv1a64Offset = 0xcbf29ce484222325ull;

// FNV-1a 64 of `bytes` bytes, continuing from `hash` (chain calls to hash
// several blocks as one).
uint64_t fnv1a64(const void* data, size_t bytes, uint64_t hash = kFnv1a64Offset);

}  // namespace rsl
