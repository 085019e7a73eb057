// Image files: EXR round trips (half/float, RGB/RGBA), Radiance RGBE decoding
// (RLE and flat scanlines written here byte by byte), PNG previews, and bad
// input that must fail with an error naming the file.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <catch2/catch.hpp>

// A private PNG decoder to check what write_png stored (static: no symbol clashes).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#pragma GCC diagnostic pop

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "tests/radiance_encoder.h"
#include "tests/raw_exr.h"
#include "tests/test_support.h"

using namespace rsl;
namespace fs = std::filesystem;

namespace {

Image random_image(int w, int h, int c, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(0.0f, 100.0f);
    Image image(w, h, c);
    for (float& v : image.pixels) v = value(rng);
    return image;
}

int count_files(const fs::path& dir) {
    int n = 0;
    for (auto& entry : fs::directory_iterator(dir)) { (void)entry; ++n; }
    return n;
}

using test::encode_radiance;
using test::radiance_header;
using test::Rgbe;

// Radiance's decoding rule, written out: (m + 0.5) · 2^(e − 136), 0 when e = 0.
float rgbe_value(unsigned char m, unsigned char e) { return e == 0 ? 0.0f : (m + 0.5f) * std::ldexp(1.0f, e - 136); }

std::vector<Rgbe> random_rgbe(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<Rgbe> pixels(size_t(w) * h);
    for (size_t k = 0; k < pixels.size(); ++k) {
        // Long constant stretches exercise runs; random ones exercise literals.
        if (k % 40 < 20) pixels[k] = Rgbe{200, 100, 50, 130};
        else pixels[k] = Rgbe{(unsigned char)(128 + rng() % 128), (unsigned char)(rng() % 256),
                              (unsigned char)(rng() % 256), (unsigned char)(120 + rng() % 16)};
    }
    pixels[3] = Rgbe{0, 0, 0, 0};  // exact black
    return pixels;
}

void check_decoded(const Image& image, const std::vector<Rgbe>& pixels) {
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Rgbe& p = pixels[size_t(y) * image.width + x];
            const float* v = image.at(x, y);
            REQUIRE(v[0] == rgbe_value(p.r, p.e));
            REQUIRE(v[1] == rgbe_value(p.g, p.e));
            REQUIRE(v[2] == rgbe_value(p.b, p.e));
        }
}

}  // namespace

TEST_CASE("EXR round trip keeps float pixels exactly, RGB and RGBA", "[image][exr]") {
    const fs::path dir = test::scratch_dir("image_exr_float");
    for (int channels : {3, 4}) {
        const Image image = random_image(37, 19, channels, 7 + channels);
        const fs::path path = dir / fmt::format("float{}.exr", channels);
        write_exr(path, image);
        const Image back = read_exr(path);
        REQUIRE(back.width == 37);
        REQUIRE(back.height == 19);
        REQUIRE(back.channels == channels);
        CHECK(back.pixels == image.pixels);
        CHECK(read_hdr_image(path).pixels == image.pixels);
    }
    CHECK(count_files(dir) == 2);  // no temporaries left
    fs::remove_all(dir);
}

TEST_CASE("EXR half files read back within half precision", "[image][exr]") {
    const fs::path dir = test::scratch_dir("image_exr_half");
    for (int channels : {3, 4}) {
        const Image image = random_image(32, 16, channels, 3);  // 2:1, as its lat-long attribute says
        const fs::path path = dir / "half.exr";
        write_exr(path, image, ExrWriteOptions{.half = true, .envmap = EnvmapKind::LatLong});
        const Image back = read_exr(path);
        REQUIRE(back.channels == channels);
        REQUIRE(back.pixels.size() == image.pixels.size());
        double worst = 0;
        for (size_t k = 0; k < image.pixels.size(); ++k)
            worst = std::max(worst, std::abs(double(back.pixels[k]) - image.pixels[k]) / image.pixels[k]);
        CHECK(worst <= 1.0 / 2048);  // half has an 11-bit significand
        CHECK(worst > 0.0);          // and it really was stored as half
        CHECK(read_exr_envmap_kind(path) == EnvmapKind::LatLong);
    }
    fs::remove_all(dir);
}

TEST_CASE("Radiance RGBE: RLE and flat scanlines decode to Radiance's values", "[image][hdr]") {
    const fs::path dir = test::scratch_dir("image_hdr");
    const int w = 70, h = 5;
    const std::vector<Rgbe> pixels = random_rgbe(w, h, 11);
    for (bool rle : {true, false}) {
        const fs::path path = dir / (rle ? "rle.hdr" : "flat.hdr");
        write_file_atomically(path, encode_radiance(w, h, pixels, rle));
        const Image image = read_hdr_image(path);
        REQUIRE(image.width == w);
        REQUIRE(image.height == h);
        REQUIRE(image.channels == 3);
        check_decoded(image, pixels);
    }
    // A known value: mantissa 128, exponent 129 → (128 + 0.5) / 128.
    CHECK(rgbe_value(128, 129) == Approx(1.00390625));
    fs::remove_all(dir);
}

TEST_CASE("Radiance EXPOSURE header divides the stored values", "[image][hdr]") {
    const fs::path dir = test::scratch_dir("image_hdr_exposure");
    std::vector<Rgbe> pixels(8 * 2, Rgbe{128, 64, 32, 129});
    std::string bytes = encode_radiance(8, 2, pixels, true);
    bytes.insert(bytes.find("\n\n") + 1, "EXPOSURE=2.0\n");
    write_file_atomically(dir / "e.hdr", bytes);
    const Image image = read_radiance_hdr(dir / "e.hdr");
    CHECK(image.at(5, 1)[0] == Approx(rgbe_value(128, 129) / 2));
    fs::remove_all(dir);
}

TEST_CASE("Bad Radiance files give errors naming the file and the scanline", "[image][hdr][bad]") {
    const fs::path dir = test::scratch_dir("image_hdr_bad");
    const int w = 32, h = 4;
    const std::string good = encode_radiance(w, h, random_rgbe(w, h, 5), true);
    auto expect_error = [&](const std::string& name, const std::string& bytes, const std::string& words) {
        const fs::path path = dir / name;
        write_file_atomically(path, bytes);
        CHECK_THROWS_WITH(read_hdr_image(path), Catch::Contains(name) && Catch::Contains(words));
    };
    expect_error("truncated.hdr", good.substr(0, good.size() - 20), "scanline 3");
    expect_error("truncated_header.hdr", good.substr(0, 30), "header");
    const size_t data = good.find("+X 32\n") + 6;
    std::string bad_width = good;
    bad_width[data + 3] = 31;  // first scanline claims width 31
    expect_error("bad_width.hdr", bad_width, "scanline 0 has width 31");
    std::string bad_run = good;
    bad_run[data + 4] = char(128 + 100);  // a run longer than the scanline
    expect_error("bad_run.hdr", bad_run, "bad run length");
    std::string zero_run = good;
    zero_run[data + 4] = 0;
    expect_error("zero_run.hdr", zero_run, "bad run length 0");
    std::string flipped = good;
    flipped.replace(flipped.find("-Y 4 +X 32"), 10, "+Y 4 +X 32");
    expect_error("flipped.hdr", flipped, "orientation");
    std::string xyze = good;
    xyze.replace(xyze.find("32-bit_rle_rgbe"), 15, "32-bit_rle_xyze");
    expect_error("xyze.hdr", xyze, "32-bit_rle_xyze");
    expect_error("empty_size.hdr", radiance_header(0, 4), "empty");
    expect_error("empty.hdr", "", "empty");
    expect_error("garbage.hdr", "#?RADIANCE\n\n-Y 2 +X 2\n", "truncated");
    fs::remove_all(dir);
}

TEST_CASE("Corrupt, mislabeled and non-RGB EXR files are refused by name", "[image][exr][bad]") {
    const fs::path dir = test::scratch_dir("image_exr_bad");
    const Image image = random_image(64, 64, 3, 1);
    write_exr(dir / "good.exr", image);
    const std::string bytes = read_file(dir / "good.exr");

    write_file_atomically(dir / "truncated.exr", bytes.substr(0, bytes.size() / 2));
    CHECK_THROWS_WITH(read_hdr_image(dir / "truncated.exr"), Catch::Contains("truncated.exr"));
    std::string corrupt = bytes;
    for (size_t k = bytes.size() / 2; k < bytes.size(); k += 7) corrupt[k] = char(corrupt[k] ^ 0x5a);
    write_file_atomically(dir / "corrupt.exr", corrupt);
    CHECK_THROWS_WITH(read_hdr_image(dir / "corrupt.exr"), Catch::Contains("corrupt.exr"));
    write_file_atomically(dir / "header_only.exr", bytes.substr(0, 40));
    CHECK_THROWS_WITH(read_hdr_image(dir / "header_only.exr"), Catch::Contains("header_only.exr"));

    // Mislabeled: EXR content named .hdr, Radiance content named .exr.
    write_file_atomically(dir / "really_exr.hdr", bytes);
    CHECK_THROWS_WITH(read_hdr_image(dir / "really_exr.hdr"),
                      Catch::Contains("really_exr.hdr") && Catch::Contains("mislabeled") && Catch::Contains("OpenEXR"));
    write_file_atomically(dir / "really_hdr.exr", encode_radiance(8, 1, std::vector<Rgbe>(8, Rgbe{1, 1, 1, 128}), true));
    CHECK_THROWS_WITH(read_hdr_image(dir / "really_hdr.exr"),
                      Catch::Contains("really_hdr.exr") && Catch::Contains("mislabeled") && Catch::Contains("Radiance"));
    write_file_atomically(dir / "text.exr", "hello");
    CHECK_THROWS_WITH(read_hdr_image(dir / "text.exr"), Catch::Contains("text.exr") && Catch::Contains("magic"));
    CHECK_THROWS_WITH(read_hdr_image(dir / "missing.exr"), Catch::Contains("missing.exr"));

    // A luminance-only file is a valid EXR but not an environment.
    {
        Imf::Header header(4, 4);
        header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
        std::vector<float> y(16, 1.0f);
        Imf::FrameBuffer frame;
        frame.insert("Y", Imf::Slice(Imf::FLOAT, (char*)y.data(), sizeof(float), 4 * sizeof(float)));
        Imf::OutputFile file((dir / "luminance.exr").c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(4);
    }
    CHECK_THROWS_WITH(read_exr(dir / "luminance.exr"),
                      Catch::Contains("luminance.exr") && Catch::Contains("{Y}") && Catch::Contains("RGB"));
    fs::remove_all(dir);
}

TEST_CASE("NaN, infinite and negative radiance are refused with the pixel position", "[image][bad]") {
    const fs::path dir = test::scratch_dir("image_nan");
    struct Case {
        float value;
        const char* word;
    };
    for (const Case& c : {Case{std::nanf(""), "NaN"}, Case{INFINITY, "infinite"}, Case{-1.0f, "negative"}}) {
        Image image = random_image(8, 6, 3, 2);
        image.at(5, 4)[1] = c.value;
        const fs::path path = dir / fmt::format("bad_{}.exr", c.word);
        test::write_unchecked_exr(path, image);  // as another program may write it
        CHECK_THROWS_WITH(read_hdr_image(path), Catch::Contains(path.filename().string()) && Catch::Contains(c.word) &&
                                                    Catch::Contains("x=5, y=4") && Catch::Contains("channel G"));
    }
    fs::remove_all(dir);
}

TEST_CASE("write_exr refuses what rsl's readers refuse: NaN, Inf, values past 1e15; nothing is written",
          "[image][bad]") {
    const fs::path dir = test::scratch_dir("image_write_nan");
    struct Case {
        float value;
        const char* word;
    };
    for (const Case& c : {Case{std::nanf(""), "NaN"}, Case{INFINITY, "infinite"}, Case{-INFINITY, "infinite"},
                          Case{2e15f, "too large"}}) {
        Image image = random_image(8, 6, 4, 2);
        image.at(5, 4)[1] = c.value;
        const fs::path path = dir / "bad.exr";
        INFO(c.value);
        CHECK_THROWS_WITH(write_exr(path, image), Catch::Contains("bad.exr") && Catch::Contains(c.word) &&
                                                      Catch::Contains("x=5, y=4") && Catch::Contains("channel G") &&
                                                      Catch::Contains("nothing written"));
        CHECK_THROWS_WITH(write_exr_and_png(path, image), Catch::Contains(c.word));
        CHECK(fs::is_empty(dir));  // neither the EXR nor its PNG
    }
    Image largest = random_image(8, 6, 3, 2);
    largest.at(1, 1)[0] = kMaxRadiance;
    write_exr(dir / "largest.exr", largest);
    CHECK(read_exr(dir / "largest.exr").at(1, 1)[0] == kMaxRadiance);  // the writer's limit is the reader's
    fs::remove_all(dir);
}

TEST_CASE("Failed writes leave no partial output", "[image][bad]") {
    const fs::path dir = test::scratch_dir("image_partial");
    CHECK_THROWS_WITH(write_exr(dir / "empty.exr", Image()), Catch::Contains("empty.exr"));
    CHECK_THROWS_WITH(write_png(dir / "empty.png", Image()), Catch::Contains("empty.png"));
    Image two_channels(4, 4, 2);
    CHECK_THROWS_WITH(write_exr(dir / "two.exr", two_channels), Catch::Contains("two.exr"));
    Image short_buffer(4, 4, 3);
    short_buffer.pixels.resize(10);
    CHECK_THROWS_WITH(write_exr(dir / "short.exr", short_buffer), Catch::Contains("short.exr"));
    CHECK(count_files(dir) == 0);
    fs::remove_all(dir);
}

TEST_CASE("PNG previews are tone mapped sRGB with optional alpha", "[image][png]") {
    const fs::path dir = test::scratch_dir("image_png");
    CHECK(linear_to_srgb8(0.0f) == 0);
    CHECK(linear_to_srgb8(1.0f) == 255);
    CHECK(linear_to_srgb8(0.5f) == 188);  // 1.055·0.5^(1/2.4) − 0.055 = 0.7354
    CHECK(linear_to_srgb8(0.002f) == 7);  // linear segment: 12.92·0.002·255 = 6.6
    CHECK(linear_to_srgb8(std::nanf("")) == 0);

    auto decode = [](const fs::path& path, int& w, int& h, int& c) {
        const std::string png = read_file(path);
        unsigned char* data = stbi_load_from_memory((const unsigned char*)png.data(), int(png.size()), &w, &h, &c, 0);
        REQUIRE(data != nullptr);
        std::vector<unsigned char> bytes(data, data + size_t(w) * h * c);
        stbi_image_free(data);
        return bytes;
    };
    int w = 0, h = 0, c = 0;
    Image image(4, 2, 3);
    image.set_rgb(0, 0, Color(0.25f, 4.0f, 0.0f));
    image.set_rgb(3, 1, Color(0.125f));
    write_png(dir / "e1.png", image, ToneMap{.exposure = 1.0f});  // × 2
    std::vector<unsigned char> bytes = decode(dir / "e1.png", w, h, c);
    REQUIRE((w == 4 && h == 2 && c == 3));
    CHECK(int(bytes[0]) == 188);  // 0.5
    CHECK(int(bytes[1]) == 255);  // clipped
    CHECK(int(bytes[2]) == 0);
    CHECK(int(bytes[(1 * 4 + 3) * 3]) == int(linear_to_srgb8(0.25f)));

    // RGBA: premultiplied colour becomes straight alpha.
    Image rgba(2, 1, 4);
    float* p = rgba.at(1, 0);
    p[0] = p[1] = p[2] = 0.25f;
    p[3] = 0.5f;
    write_png(dir / "alpha.png", rgba);
    bytes = decode(dir / "alpha.png", w, h, c);
    REQUIRE((w == 2 && h == 1 && c == 4));
    CHECK(int(bytes[3]) == 0);
    CHECK(int(bytes[4]) == 188);
    CHECK(int(bytes[7]) == 128);

    // Auto exposure: the 99th luminance percentile goes to 0.9.
    Image ramp(100, 1, 3);
    for (int x = 0; x < 100; ++x) ramp.set_rgb(x, 0, Color(float(x + 1)));
    write_png(dir / "auto.png", ramp, ToneMap{.auto_exposure = true});
    bytes = decode(dir / "auto.png", w, h, c);
    CHECK(int(bytes[98 * 3]) == int(linear_to_srgb8(0.9f)));
    CHECK(int(bytes[49 * 3]) == int(linear_to_srgb8(0.9f * 50 / 99)));
    // Auto exposure on an all-black image must not divide by zero.
    write_png(dir / "black.png", Image(3, 3, 4), ToneMap{.auto_exposure = true});
    write_exr_and_png(dir / "both.exr", random_image(5, 5, 4, 9), ToneMap{.auto_exposure = true});
    CHECK(fs::exists(dir / "both.exr"));
    CHECK(fs::exists(dir / "both.png"));
    fs::remove_all(dir);
}
