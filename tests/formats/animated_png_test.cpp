// The animated PNG writer, read back by a chunk walker of the test's own and
// stb_image: frame count, sequence numbers, CRCs, delay, and each frame's
// pixels decoded from its own chunks.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "src/formats/animated_png.h"
#include "tests/png_test_support.h"
#include "tests/test_support.h"

using namespace rsl;

using namespace rsl::test;

TEST_CASE("an animated PNG holds every frame, each decoding to its own pixels", "[core][apng]") {
    const int width = 7, height = 5;
    for (const int channels : {3, 4}) {
        INFO("channels " << channels);
        std::mt19937 rng(57 + channels);
        std::uniform_int_distribution<int> byte(0, 255);
        std::vector<std::vector<unsigned char>> frames(4);
        AnimatedPng animation(width, height, channels);
        for (auto& frame : frames) {
            frame.resize(size_t(width) * height * channels);
            for (auto& value : frame) value = (unsigned char)byte(rng);
            animation.add_frame(frame);
        }
        REQUIRE(animation.frame_count() == 4);
        const std::string file = animation.encode(0.25);
        const std::vector<Chunk> chunks = chunks_of(file);

        REQUIRE(chunks.front().type == "IHDR");
        REQUIRE(chunks.back().type == "IEND");
        REQUIRE(chunks[1].type == "acTL");
        CHECK(be32(chunks[1].data, 0) == 4);  // frames
        CHECK(be32(chunks[1].data, 4) == 0);  // loops forever
        // fcTL and fdAT share one run of sequence numbers 0, 1, 2, …; each frame's data follows its fcTL.
        uint32_t next_sequence = 0;
        std::vector<std::string> frame_data;
        for (const Chunk& chunk : chunks) {
            if (chunk.type == "fcTL") {
                REQUIRE(chunk.data.size() == 26);
                CHECK(be32(chunk.data, 0) == next_sequence++);
                CHECK(be32(chunk.data, 4) == uint32_t(width));
                CHECK(be32(chunk.data, 8) == uint32_t(height));
                const int delay_num = uint8_t(chunk.data[20]) << 8 | uint8_t(chunk.data[21]);
                const int delay_den = uint8_t(chunk.data[22]) << 8 | uint8_t(chunk.data[23]);
                CHECK(double(delay_num) / delay_den == Approx(0.25));
                frame_data.emplace_back();
            } else if (chunk.type == "IDAT") {
                REQUIRE(frame_data.size() == 1);
                frame_data.back() += chunk.data;
            } else if (chunk.type == "fdAT") {
                REQUIRE(frame_data.size() >= 2);
                CHECK(be32(chunk.data, 0) == next_sequence++);
                frame_data.back() += chunk.data.substr(4);
            }
        }
        REQUIRE(frame_data.size() == 4);

        // The whole file read as a still PNG is the first frame.
        int w = 0, h = 0;
        CHECK(decode(file, channels, w, h) == frames[0]);
        CHECK((w == width && h == height));
        // Each frame's zlib data, put in a PNG of its own, decodes to that frame.
        for (size_t f = 0; f < frames.size(); ++f) {
            INFO("frame " << f);
            const std::string still = std::string("\x89PNG\r\n\x1a\n", 8) + chunk_bytes("IHDR", chunks[0].data) +
                                      chunk_bytes("IDAT", frame_data[f]) + chunk_bytes("IEND", "");
            CHECK(decode(still, channels, w, h) == frames[f]);
        }
    }
}

TEST_CASE("an animated PNG refuses an empty sequence", "[core][apng]") {
    AnimatedPng animation(2, 2, 3);
    CHECK(test::error_of([&] { (void)animation.encode(0.1); }).find("at least one frame") != std::string::npos);
}
