#pragma once
// Mutated .rslf/.rslv files would almost all stop at their checksum; the
// fuzzers make the checksum (and a field file's parameter hash) right again
// before the reader sees the bytes, so that mutations reach the parser
// behind it. Tests that replay fuzz inputs apply the same fix-up.
#include <cstdint>
#include <cstring>
#include <string>

#include "src/formats/binary_io.h"

namespace rsl::fuzz {

// The last 8 bytes become the FNV-1a 64 of everything before them.
inline void fix_trailing_checksum(std::string& bytes) {
    if (bytes.size() < 8) return;
    const uint64_t checksum = fnv1a64(bytes.data(), bytes.size() - 8);
    std::memcpy(bytes.data() + bytes.size() - 8, &checksum, 8);
}

// A field file (src/fields/field_file.h): the parameter hash at byte 24 matches
// the u32-length-prefixed parameter JSON at byte 32, then the checksum.
inline void fix_field_file(std::string& bytes) {
    constexpr size_t kHashAt = 24, kLengthAt = 32;
    if (bytes.size() >= kLengthAt + 4) {
        uint32_t length = 0;
        std::memcpy(&length, bytes.data() + kLengthAt, 4);
        if (length <= bytes.size() - kLengthAt - 4) {
            const uint64_t hash = fnv1a64(bytes.data() + kLengthAt + 4, length);
            std::memcpy(bytes.data() + kHashAt, &hash, 8);
        }
    }
    fix_trailing_checksum(bytes);
}

}  // namespace rsl::fuzz
