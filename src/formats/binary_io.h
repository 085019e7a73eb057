#pragma once
// Little-endian binary files built in memory: a writer that appends values, a
// bounds-checked reader whose errors name the file, and the FNV-1a 64
// checksum (src/core/checksum.h) that the project's binary formats (.rslf
// field files, .rslv vertex colours) end with. Values are written in the
// machine's byte order, which on every platform rsl builds for is little-endian.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

#include "src/core/checksum.h"
#include "src/core/error.h"

namespace rsl {

static_assert(std::endian::native == std::endian::little, "rsl's binary files are little-endian");

class BinaryWriter {
public:
    template <typename T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    void put_bytes(const void* data, size_t count) {
        if (count) bytes_.append(static_cast<const char*>(data), count);  // data may be null when empty
    }
    // u32 length, then the bytes.
    void put_string(std::string_view s) {
        put(uint32_t(s.size()));
        bytes_.append(s);
    }
    // Appends the FNV-1a 64 of everything written so far; returns the bytes.
    const std::string& finish_with_checksum() {
        put(fnv1a64(bytes_.data(), bytes_.size()));
        return bytes_;
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

// Whether `bytes` ends with the FNV-1a 64 of everything before it.
bool has_valid_checksum(std::string_view bytes);
// The checksum stored in the last 8 bytes (0 when there are fewer).
uint64_t stored_checksum(std::string_view bytes);

// Reads bytes [0, end) of a file's contents; reading past `end` throws an
// rsl::Error "<path>: truncated or corrupt: the file ends inside the <what>".
// `end` is usually the size less the trailing checksum.
class BinaryReader {
public:
    BinaryReader(const std::filesystem::path& path, std::string_view bytes, size_t end)
        : path_(path), bytes_(bytes), end_(std::min(end, bytes.size())) {}

    template <typename T>
    T get(const char* what = "payload") {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        get_bytes(&value, sizeof(T), what);
        return value;
    }
    void get_bytes(void* out, size_t count, const char* what = "payload") {
        need(count, what);
        if (count == 0) return;  // `out` may then be an empty vector's null data(); memcpy forbids null
        std::memcpy(out, bytes_.data() + at_, count);
        at_ += count;
    }
    // u32 length, then the bytes.
    std::string get_string(const char* what) {
        const uint32_t size = get<uint32_t>(what);
        need(size, what);
        std::string s(bytes_.data() + at_, size);
        at_ += size;
        return s;
    }
    size_t position() const { return at_; }
    size_t remaining() const { return end_ - at_; }

private:
    void need(size_t count, const char* what) const {
        if (count > remaining()) throw_file_error(path_, "truncated or corrupt: the file ends inside the {}", what);
    }

    std::filesystem::path path_;  // a copy: callers may pass a temporary
    std::string_view bytes_;      // the caller keeps the bytes alive
    size_t end_;
    size_t at_ = 0;
};

}  // namespace rsl
