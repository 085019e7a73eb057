#include "demos/contact_sheet.h"

#include <algorithm>

// A header of static functions; not all of them are used here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

#include "src/core/error.h"

namespace rsl::demos {

namespace {
constexpr int kGlyphHeight = 12;  // stb_easy_font's line height at scale 1

void fill_rect(Image& image, int x0, int y0, int x1, int y1, const Color& color) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0);
    x1 = std::min(x1, image.width), y1 = std::min(y1, image.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) image.set_rgb(x, y, color);
}
}  // namespace

int text_height(int scale) { return kGlyphHeight * scale; }

void draw_text(Image& image, int x, int y, const std::string& text, const Color& color, int scale) {
    // stb_easy_font emits axis-aligned quads (4 vertices of 16 bytes each);
    // ~270 bytes per character is its documented worst case.
    std::vector<char> buffer(270 * (text.size() + 1));
    std::string copy = text;
    unsigned char rgba[4] = {255, 255, 255, 255};
    const int quads = stb_easy_font_print(0, 0, copy.data(), rgba, buffer.data(), int(buffer.size()));
    struct Vertex {
        float x, y, z;
        unsigned char c[4];
    };
    const auto* vertices = reinterpret_cast<const Vertex*>(buffer.data());
    for (int q = 0; q < quads; ++q) {
        const Vertex* v = vertices + 4 * q;
        const float lx = std::min({v[0].x, v[1].x, v[2].x, v[3].x}), hx = std::max({v[0].x, v[1].x, v[2].x, v[3].x});
        const float ly = std::min({v[0].y, v[1].y, v[2].y, v[3].y}), hy = std::max({v[0].y, v[1].y, v[2].y, v[3].y});
        fill_rect(image, x + int(lx) * scale, y + int(ly) * scale, x + int(hx) * scale, y + int(hy) * scale, color);
    }
}

Image make_contact_sheet(const std::vector<Image>& tiles, const std::vector<std::string>& labels,
                         const ContactSheetLayout& layout) {
    RSL_CHECK(!tiles.empty());
    RSL_CHECK(labels.empty() || labels.size() == tiles.size());
    RSL_CHECK_GE(layout.columns, 1);
    RSL_CHECK_GE(layout.gap, 0);
    const int w = tiles.front().width, h = tiles.front().height;
    for (const Image& tile : tiles) {
        RSL_CHECK_EQ(tile.width, w);
        RSL_CHECK_EQ(tile.height, h);
        RSL_CHECK_GE(tile.channels, 3);
    }
    const bool labelled = std::any_of(labels.begin(), labels.end(), [](const std::string& s) { return !s.empty(); });
    const int label_band = labelled ? text_height(layout.label_scale) + layout.gap : 0;
    const int columns = std::min<int>(layout.columns, int(tiles.size()));
    const int rows = (int(tiles.size()) + columns - 1) / columns;
    const int cell_w = w + layout.gap, cell_h = h + label_band + layout.gap;
    Image sheet(layout.gap + columns * cell_w, layout.gap + rows * cell_h, 3);
    fill_rect(sheet, 0, 0, sheet.width, sheet.height, layout.background);
    for (size_t i = 0; i < tiles.size(); ++i) {
        const int x0 = layout.gap + int(i % columns) * cell_w, y0 = layout.gap + int(i / columns) * cell_h;
        const Image& tile = tiles[i];
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) sheet.set_rgb(x0 + x, y0 + y, tile.rgb(x, y));
        if (labelled && !labels[i].empty())
            draw_text(sheet, x0 + 2, y0 + h + layout.gap / 2, labels[i], layout.label_color, layout.label_scale);
    }
    return sheet;
}

Image downsample(const Image& image, int factor) {
    RSL_CHECK_GE(factor, 1);
    RSL_CHECK_GE(image.channels, 3);
    Image out(std::max(1, image.width / factor), std::max(1, image.height / factor), 3);
    const float weight = 1.0f / float(factor * factor);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            Color sum(0);
            for (int dy = 0; dy < factor; ++dy)
                for (int dx = 0; dx < factor; ++dx)
                    sum += image.rgb(std::min(x * factor + dx, image.width - 1),
                                     std::min(y * factor + dy, image.height - 1));
            out.set_rgb(x, y, sum * weight);
        }
    return out;
}

}  // namespace rsl::demos
