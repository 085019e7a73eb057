#pragma once
// A tiny Radiance (.hdr) writer, independent of the reader in
// src/formats/image_file.cpp so that tests check the reader decodes what it
// writes (tests/formats/image_file_test.cpp), and so that hostile-input tests
// and the fuzz seeds (fuzz/seeds) can build files byte by byte: flat or new-style
// run-length encoded scanlines.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "src/core/image.h"

namespace rsl::test {

struct Rgbe {
    unsigned char r, g, b, e;
};

// Radiance's setcolr: the largest component's exponent is shared, each
// mantissa is value / 2^(e − 136) rounded down; black below 1e-32.
inline Rgbe to_rgbe(float r, float g, float b) {
    const float v = std::max({r, g, b});
    if (!(v > 1e-32f)) return Rgbe{0, 0, 0, 0};
    int exponent = 0;
    const float scale = std::frexp(v, &exponent) * 256.0f / v;
    return Rgbe{(unsigned char)(r * scale), (unsigned char)(g * scale), (unsigned char)(b * scale),
                (unsigned char)(exponent + 128)};
}

inline std::string radiance_header(int w, int h) {
    return "#?RADIANCE\n# test file\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) +
           "\n";
}

// One plane of a new-style RLE scanline: runs of ≥ 3 equal bytes become runs.
inline void encode_plane(std::string& out, const std::vector<unsigned char>& plane) {
    size_t x = 0;
    while (x < plane.size()) {
        size_t run = 1;
        while (x + run < plane.size() && plane[x + run] == plane[x] && run < 127) ++run;
        if (run >= 3) {
            out += char(128 + run);
            out += char(plane[x]);
            x += run;
            continue;
        }
        size_t start = x, literal = 0;
        while (x < plane.size() && literal < 128) {
            size_t ahead = 1;
            while (x + ahead < plane.size() && plane[x + ahead] == plane[x] && ahead < 3) ++ahead;
            if (ahead >= 3) break;
            ++x;
            ++literal;
        }
        out += char(literal);
        for (size_t k = start; k < start + literal; ++k) out += char(plane[k]);
    }
}

// The whole file: header, then h scanlines of w pixels (row 0 at the top).
inline std::string encode_radiance(int w, int h, const std::vector<Rgbe>& pixels, bool rle) {
    std::string out = radiance_header(w, h);
    for (int y = 0; y < h; ++y) {
        const Rgbe* row = &pixels[size_t(y) * w];
        if (!rle) {
            for (int x = 0; x < w; ++x) out += std::string{char(row[x].r), char(row[x].g), char(row[x].b), char(row[x].e)};
            continue;
        }
        out += std::string{2, 2, char(w >> 8), char(w & 255)};
        for (int c = 0; c < 4; ++c) {
            std::vector<unsigned char> plane(w);
            for (int x = 0; x < w; ++x) plane[x] = c == 0 ? row[x].r : c == 1 ? row[x].g : c == 2 ? row[x].b : row[x].e;
            encode_plane(out, plane);
        }
    }
    return out;
}

// An RGB image as a Radiance file.
inline std::string encode_radiance(const Image& image, bool rle) {
    std::vector<Rgbe> pixels(size_t(image.width) * image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            pixels[size_t(y) * image.width + x] = to_rgbe(p[0], p[1], p[2]);
        }
    return encode_radiance(image.width, image.height, pixels, rle);
}

}  // namespace rsl::test
