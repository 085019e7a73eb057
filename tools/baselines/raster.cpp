// Raster figures: bitmap text, lines, contact sheets, log-scale line plots.
#include "tools/baselines/raster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "src/core/error.h"

namespace rsl::raster {

namespace {

// 5×7 glyphs, one byte per row, bit 4 = leftmost column.
const std::map<char, std::array<uint8_t, 7>>& font() {
    static const std::map<char, std::array<uint8_t, 7>> glyphs = {
        {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}}, {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
        {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}}, {'D', {0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E}},
        {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}}, {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
        {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
        {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
        {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
        {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
        {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
        {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
        {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}}, {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
        {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
        {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}}, {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
        {'Y', {0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04}}, {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
        {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
        {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
        {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
        {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
        {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
        {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
        {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}}, {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
        {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}}, {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
        {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
        {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
        {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}}, {'x', {0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x00}},
    };
    return glyphs;
}

void blend_pixel(Image& image, int x, int y, const Color& color) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    float* p = image.at(x, y);
    p[0] = color.r, p[1] = color.g, p[2] = color.b;
    if (image.channels == 4) p[3] = 1.0f;
}

}  // namespace

void fill_rect(Image& image, int x0, int y0, int x1, int y1, const Color& color) {
    for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) blend_pixel(image, x, y, color);
}

void draw_line(Image& image, float x0, float y0, float x1, float y1, const Color& color, int thickness) {
    const int steps = int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    const int half = thickness / 2;
    for (int s = 0; s <= steps; ++s) {
        const float t = float(s) / float(steps);
        const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
        fill_rect(image, x - half, y - half, x - half + thickness, y - half + thickness, color);
    }
}

int text_width(const std::string& text, int scale) { return int(text.size()) * 6 * scale; }

void draw_text(Image& image, int x, int y, const std::string& text, const Color& color, int scale) {
    for (size_t c = 0; c < text.size(); ++c) {
        char ch = text[c];
        if (ch != 'x' && ch >= 'a' && ch <= 'z') ch = char(ch - 'a' + 'A');
        const auto it = font().find(ch);
        if (it == font().end()) continue;
        for (int row = 0; row < 7; ++row)
            for (int col = 0; col < 5; ++col)
                if (it->second[row] & (0x10 >> col))
                    fill_rect(image, x + int(c) * 6 * scale + col * scale, y + row * scale,
                              x + int(c) * 6 * scale + (col + 1) * scale, y + (row + 1) * scale, color);
    }
}

Image contact_sheet(const std::vector<Image>& tiles, const std::vector<std::string>& labels, int columns, float gain) {
    RSL_CHECK(!tiles.empty());
    RSL_CHECK_EQ(tiles.size(), labels.size());
    RSL_CHECK_GE(columns, 1);
    const int w = tiles[0].width, h = tiles[0].height, band = 14, gap = 4;
    const int rows = int((tiles.size() + columns - 1) / columns);
    Image sheet(columns * (w + gap) + gap, rows * (h + band + gap) + gap, 3);
    fill_rect(sheet, 0, 0, sheet.width, sheet.height, Color(0.02f));
    for (size_t t = 0; t < tiles.size(); ++t) {
        const Image& tile = tiles[t];
        RSL_CHECK(tile.width == w && tile.height == h);
        const int x0 = gap + int(t % columns) * (w + gap), y0 = gap + int(t / columns) * (h + band + gap);
        draw_text(sheet, x0 + 2, y0 + 3, labels[t], Color(1.0f), 1);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) sheet.set_rgb(x0 + x, y0 + band + y, tile.rgb(x, y) * gain);
    }
    return sheet;
}

namespace {

// A log10 axis spanning [lo, hi] (both > 0) in whole decades.
struct LogAxis {
    int first = 0, decades = 1;
    LogAxis(double lo, double hi) {
        if (!(hi > 0) || !(lo > 0)) lo = 0.01, hi = 1;
        first = int(std::floor(std::log10(lo)));
        decades = std::max(1, int(std::ceil(std::log10(hi))) - first);
    }
    double fraction(double v) const { return (std::log10(std::max(v, 1e-30)) - first) / decades; }
    static std::string label(int decade) {
        return decade >= 0 ? fmt::format("{:g}", std::pow(10.0, decade)) : fmt::format("1E{}", decade);
    }
};

}  // namespace

Image line_plot(const std::vector<Series>& series, const std::string& x_label, const std::string& y_label, int width,
                int height, bool log_x) {
    Image plot(width, height, 3);
    fill_rect(plot, 0, 0, width, height, Color(1.0f));
    const int left = 64, right = width - 150, top = 20, bottom = height - 44;
    double x_min = 1e30, x_max = log_x ? 0 : 1, y_min = 1e30, y_max = 0;
    for (const Series& s : series)
        for (size_t i = 0; i < s.x.size(); ++i) {
            x_max = std::max(x_max, s.x[i]);
            if (s.x[i] > 0) x_min = std::min(x_min, s.x[i]);
            if (s.y[i] > 0) y_min = std::min(y_min, s.y[i]), y_max = std::max(y_max, s.y[i]);
        }
    const LogAxis ly(y_min, y_max), lx(x_min, x_max);
    auto px = [&](double x) { return float(left + (right - left) * (log_x ? lx.fraction(x) : x / x_max)); };
    auto py = [&](double y) { return float(bottom - (bottom - top) * ly.fraction(y)); };
    const Color grid(0.85f), axis(0.0f);
    for (int d = ly.first; d <= ly.first + ly.decades; ++d) {
        for (int m = 1; m < 10 && d < ly.first + ly.decades; ++m)
            draw_line(plot, float(left), py(m * std::pow(10.0, d)), float(right), py(m * std::pow(10.0, d)),
                      m == 1 ? Color(0.7f) : grid);
        const std::string label = LogAxis::label(d);
        draw_text(plot, left - 6 - text_width(label), int(py(std::pow(10.0, d))) - 3, label, axis);
    }
    if (log_x) {
        for (int d = lx.first; d <= lx.first + lx.decades; ++d) {
            for (int m = 1; m < 10 && d < lx.first + lx.decades; ++m)
                draw_line(plot, px(m * std::pow(10.0, d)), float(top), px(m * std::pow(10.0, d)), float(bottom),
                          m == 1 ? Color(0.7f) : grid);
            const std::string label = LogAxis::label(d);
            draw_text(plot, int(px(std::pow(10.0, d))) - text_width(label) / 2, bottom + 6, label, axis);
        }
    } else {
        const double x_step = x_max > 50 ? 20 : x_max > 20 ? 10 : 5;
        for (double x = 0; x <= x_max + 1e-9; x += x_step) {
            draw_line(plot, px(x), float(top), px(x), float(bottom), grid);
            const std::string label = fmt::format("{:g}", x);
            draw_text(plot, int(px(x)) - text_width(label) / 2, bottom + 6, label, axis);
        }
    }
    draw_line(plot, float(left), float(bottom), float(right), float(bottom), axis);
    draw_line(plot, float(left), float(top), float(left), float(bottom), axis);
    draw_text(plot, (left + right - text_width(x_label)) / 2, height - 18, x_label, axis);
    draw_text(plot, 4, 4, y_label, axis);
    for (size_t k = 0; k < series.size(); ++k) {
        const Series& s = series[k];
        for (size_t i = 0; i < s.x.size(); ++i) {
            if (i > 0) draw_line(plot, px(s.x[i - 1]), py(s.y[i - 1]), px(s.x[i]), py(s.y[i]), s.color, 2);
            fill_rect(plot, int(px(s.x[i])) - 3, int(py(s.y[i])) - 3, int(px(s.x[i])) + 4, int(py(s.y[i])) + 4, s.color);
            if (i < s.labels.size()) draw_text(plot, int(px(s.x[i])) + 6, int(py(s.y[i])) - 10, s.labels[i], axis);
        }
        const int ly = top + 10 + int(k) * 16;
        fill_rect(plot, right + 12, ly, right + 30, ly + 7, s.color);
        draw_text(plot, right + 36, ly, s.name, axis);
    }
    return plot;
}

}  // namespace rsl::raster
