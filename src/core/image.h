#pragma once
// A float image in memory: RGB or RGBA, row-major, row 0 at the top. Its
// files (OpenEXR, Radiance .hdr, PNG) are read and written in
// src/formats/image_file.h.
#include <vector>

#include "src/core/math.h"

namespace rsl {

struct Image {
    int width = 0, height = 0;
    int channels = 3;           // 3 (RGB) or 4 (RGBA, alpha = coverage)
    std::vector<float> pixels;  // row-major, row 0 at the top, interleaved channels

    Image() = default;
    Image(int w, int h, int c = 3) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, 0.0f) {}

    float* at(int x, int y) { return &pixels[(size_t(y) * width + x) * channels]; }
    const float* at(int x, int y) const { return &pixels[(size_t(y) * width + x) * channels]; }
    Color rgb(int x, int y) const { const float* p = at(x, y); return Color(p[0], p[1], p[2]); }
    void set_rgb(int x, int y, const Color& c) { float* p = at(x, y); p[0] = c.r; p[1] = c.g; p[2] = c.b; }
};

}  // namespace rsl
