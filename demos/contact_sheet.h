#pragma once
// Contact sheets: a grid of equally sized frames in one image, with optional
// labels under each tile, so that a whole demo fits in one PNG (the README
// gallery, the test's overview). Works on linear images (tone mapping happens
// once, when the sheet is written), so every tile keeps the demo's exposure.
#include <string>
#include <vector>

#include "src/core/image.h"

namespace rsl::demos {

struct ContactSheetLayout {
    int columns = 4;         // tiles per row (fewer when there are fewer tiles)
    int gap = 4;             // pixels between tiles and around the border
    int label_scale = 1;     // label glyph scale (stb_easy_font glyphs are ~6×12 px at scale 1)
    Color background{0.02f};
    Color label_color{1.0f};  // linear; pass 2^-exposure for white after tone mapping
};

// Tiles must share width and height (RSL_CHECK); labels may be empty, or one
// per tile (an empty string leaves that tile unlabelled). RGB result.
Image make_contact_sheet(const std::vector<Image>& tiles, const std::vector<std::string>& labels,
                         const ContactSheetLayout& layout = {});

// Draws ASCII text with its top-left corner at (x, y), clipped to the image.
void draw_text(Image& image, int x, int y, const std::string& text, const Color& color, int scale = 1);
// Height in pixels of one line of text at `scale`.
int text_height(int scale = 1);

// Box-filtered copy of `image` reduced by an integer factor (≥ 1) in each axis;
// RGB result (alpha, if any, is dropped: colour is already premultiplied).
Image downsample(const Image& image, int factor);

}  // namespace rsl::demos
