#pragma once
// Minimal raster drawing into an rsl::Image for the comparison's figures:
// a built-in 5×7 bitmap font (upper-case letters, digits, a few symbols),
// lines, rectangles, a labelled contact sheet and a line plot with a log-scale
// y axis. No dependency beyond the Image type; values are linear RGB in [0, 1]
// meant for write_png at exposure 0.
#include <string>
#include <vector>

#include "src/formats/image_file.h"

namespace rsl::raster {

void fill_rect(Image& image, int x0, int y0, int x1, int y1, const Color& color);  // [x0, x1) × [y0, y1)
void draw_line(Image& image, float x0, float y0, float x1, float y1, const Color& color, int thickness = 1);
// Text with its top-left corner at (x, y), glyphs 6·scale pixels apart;
// lower-case letters are drawn as upper-case, unknown characters as blanks.
void draw_text(Image& image, int x, int y, const std::string& text, const Color& color, int scale = 1);
int text_width(const std::string& text, int scale = 1);

// Tiles (all the same size, RGB or RGBA) in a grid of `columns`, each scaled
// by `gain` (linear), with its label in a band above it.
Image contact_sheet(const std::vector<Image>& tiles, const std::vector<std::string>& labels, int columns, float gain);

struct Series {
    std::string name;
    Color color;
    std::vector<double> x, y;  // y > 0 (log axis)
    std::vector<std::string> labels;  // optional, one per point, drawn beside its marker
};
// Lines with square markers; y on a log10 axis spanning the data, x linear
// from 0 or (log_x) on a log10 axis too.
Image line_plot(const std::vector<Series>& series, const std::string& x_label, const std::string& y_label,
                int width = 640, int height = 420, bool log_x = false);

}  // namespace rsl::raster
