#include "src/formats/binary_io.h"

namespace rsl {

uint64_t stored_checksum(std::string_view bytes) {
    uint64_t stored = 0;
    if (bytes.size() >= sizeof(stored)) std::memcpy(&stored, bytes.data() + bytes.size() - sizeof(stored), sizeof(stored));
    return stored;
}

bool has_valid_checksum(std::string_view bytes) {
    return bytes.size() >= sizeof(uint64_t) && stored_checksum(bytes) == fnv1a64(bytes.data(), bytes.size() - sizeof(uint64_t));
}

}  // namespace rsl
