#pragma once
// PNG files the tests read back (screenshots, contact sheets) as 8-bit RGB,
// row 0 at the top.
#include <catch2/catch.hpp>

#include <stb_image.h>

#include <filesystem>
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

}  // namespace rsl::test
