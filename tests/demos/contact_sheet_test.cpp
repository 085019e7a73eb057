// Contact sheets: tile placement, labels, box downsampling, against
// brute-force expectations.
#include <catch2/catch.hpp>

#include <random>

#include "demos/contact_sheet.h"
#include "src/core/error.h"

using namespace rsl;
using namespace rsl::demos;

namespace {

Image random_image(int w, int h, int channels, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image image(w, h, channels);
    for (float& v : image.pixels) v = u(rng);
    return image;
}

}  // namespace

TEST_CASE("contact sheet places every tile at its grid cell and fills the rest with the background", "[demos]") {
    std::vector<Image> tiles;
    for (unsigned i = 0; i < 5; ++i) tiles.push_back(random_image(7, 5, i % 2 ? 4 : 3, 100 + i));
    ContactSheetLayout layout;
    layout.columns = 3;
    layout.gap = 2;
    layout.background = Color(0.25f, 0.5f, 0.75f);
    const Image sheet = make_contact_sheet(tiles, {}, layout);
    REQUIRE(sheet.width == 2 + 3 * (7 + 2));
    REQUIRE(sheet.height == 2 + 2 * (5 + 2));
    std::vector<bool> covered(size_t(sheet.width) * sheet.height, false);
    for (size_t i = 0; i < tiles.size(); ++i) {
        const int x0 = 2 + int(i % 3) * 9, y0 = 2 + int(i / 3) * 7;
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 7; ++x) {
                REQUIRE(sheet.rgb(x0 + x, y0 + y) == tiles[i].rgb(x, y));
                covered[size_t(y0 + y) * sheet.width + x0 + x] = true;
            }
    }
    for (int y = 0; y < sheet.height; ++y)
        for (int x = 0; x < sheet.width; ++x)
            if (!covered[size_t(y) * sheet.width + x]) REQUIRE(sheet.rgb(x, y) == layout.background);
}

TEST_CASE("contact sheet labels draw only in the band under their tile", "[demos]") {
    const std::vector<Image> tiles{Image(60, 20, 3), Image(60, 20, 3)};
    ContactSheetLayout layout;
    layout.columns = 2;
    layout.background = Color(0);
    layout.label_color = Color(1);
    const Image plain = make_contact_sheet(tiles, {"", ""}, layout);
    const Image labelled = make_contact_sheet(tiles, {"K=10", ""}, layout);
    REQUIRE(labelled.height == plain.height + text_height() + layout.gap);
    int lit = 0;
    for (int y = 0; y < labelled.height; ++y)
        for (int x = 0; x < labelled.width; ++x)
            if (labelled.rgb(x, y) == Color(1)) {
                ++lit;
                // First cell's label band: below the first tile, within its column.
                REQUIRE(y >= layout.gap + 20);
                REQUIRE(x < layout.gap + 60 + layout.gap);
            }
    REQUIRE(lit > 20);  // "K=10" is a few dozen pixels
    REQUIRE_THROWS_AS(make_contact_sheet(tiles, {"only one"}, layout), InternalError);  // a caller bug, not input
    REQUIRE_THROWS_AS(make_contact_sheet({Image(4, 4, 3), Image(5, 4, 3)}, {}, layout), InternalError);
}

TEST_CASE("downsample is the box average of each factor x factor block", "[demos]") {
    const Image image = random_image(13, 9, 4, 7);
    for (int factor : {1, 2, 3, 4}) {
        const Image small = downsample(image, factor);
        REQUIRE(small.channels == 3);
        REQUIRE(small.width == 13 / factor);
        REQUIRE(small.height == 9 / factor);
        for (int y = 0; y < small.height; ++y)
            for (int x = 0; x < small.width; ++x) {
                Color sum(0);
                for (int dy = 0; dy < factor; ++dy)
                    for (int dx = 0; dx < factor; ++dx) sum += image.rgb(x * factor + dx, y * factor + dy);
                const Color expected = sum / float(factor * factor);
                for (int c = 0; c < 3; ++c) REQUIRE(small.rgb(x, y)[c] == Approx(expected[c]).epsilon(1e-5));
            }
    }
}
