#pragma once
// PNG files the tests read back (screenshots, contact sheets) as 8-bit RGB,
// row 0 at the top.
#include <catch2/catch.hpp>

#include <stb_image.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rsl::test {

struct Png {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    const unsigned char* at(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};

inline Png read_png(const std::filesystem::path& path) {
    INFO(path.string());
    REQUIRE(std::filesystem::is_regular_file(path));
    Png png;
    int channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 3);
    REQUIRE(data != nullptr);
    png.rgb.assign(data, data + size_t(png.width) * png.height * 3);
    stbi_image_free(data);
    return png;
}

// Animated PNGs (APNG), read by the tests' own chunk walker.
// Bitwise CRC-32 (the PNG polynomial), independent of the writer's table.
inline uint32_t bitwise_crc(const std::string& bytes) {
    uint32_t c = 0xffffffffu;
    for (const char byte : bytes) {
        c ^= uint8_t(byte);
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

inline uint32_t be32(const std::string& s, size_t at) {
    return uint32_t(uint8_t(s[at])) << 24 | uint32_t(uint8_t(s[at + 1])) << 16 | uint32_t(uint8_t(s[at + 2])) << 8 |
           uint32_t(uint8_t(s[at + 3]));
}

struct Chunk {
    std::string type, data;
};

inline std::vector<Chunk> chunks_of(const std::string& file) {
    REQUIRE(file.size() > 8);
    REQUIRE(file.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) == 0);
    std::vector<Chunk> chunks;
    for (size_t at = 8; at < file.size();) {
        REQUIRE(at + 12 <= file.size());
        const uint32_t length = be32(file, at);
        REQUIRE(at + 12 + length <= file.size());
        Chunk chunk{file.substr(at + 4, 4), file.substr(at + 8, length)};
        CHECK(be32(file, at + 8 + length) == bitwise_crc(chunk.type + chunk.data));
        chunks.push_back(chunk);
        at += 12 + length;
    }
    return chunks;
}

inline std::string chunk_bytes(const std::string& type, const std::string& data) {
    std::string out;
    for (int shift = 24; shift >= 0; shift -= 8) out += char((data.size() >> shift) & 0xff);
    out += type + data;
    const uint32_t crc = bitwise_crc(type + data);
    for (int shift = 24; shift >= 0; shift -= 8) out += char((crc >> shift) & 0xff);
    return out;
}

// An 8-bit image decoded by stb_image, as `channels` channels.
inline std::vector<unsigned char> decode(const std::string& png, int channels, int& width, int& height) {
    int file_channels = 0;
    unsigned char* data = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()), int(png.size()),
                                                &width, &height, &file_channels, channels);
    REQUIRE(data != nullptr);
    std::vector<unsigned char> pixels(data, data + size_t(width) * height * channels);
    stbi_image_free(data);
    return pixels;
}

// Each frame of an animated PNG as a still PNG of its own (IHDR, the frame's
// zlib data as IDAT, IEND), checking chunk CRCs and the shared run of
// sequence numbers on the way.
inline std::vector<std::string> apng_frames(const std::string& file) {
    const std::vector<Chunk> chunks = chunks_of(file);
    REQUIRE(chunks.front().type == "IHDR");
    uint32_t next_sequence = 0;
    std::vector<std::string> data;
    for (const Chunk& chunk : chunks) {
        if (chunk.type == "fcTL") {
            CHECK(be32(chunk.data, 0) == next_sequence++);
            data.emplace_back();
        } else if (chunk.type == "IDAT" && !data.empty()) {
            data.back() += chunk.data;
        } else if (chunk.type == "fdAT") {
            REQUIRE(!data.empty());
            CHECK(be32(chunk.data, 0) == next_sequence++);
            data.back() += chunk.data.substr(4);
        }
    }
    std::vector<std::string> stills;
    for (const std::string& frame : data)
        stills.push_back(std::string("\x89PNG\r\n\x1a\n", 8) + chunk_bytes("IHDR", chunks.front().data) +
                         chunk_bytes("IDAT", frame) + chunk_bytes("IEND", ""));
    return stills;
}

}  // namespace rsl::test
