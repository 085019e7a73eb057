#pragma once
// Animated PNG (APNG, https://wiki.mozilla.org/APNG_Specification): an image
// sequence in one file that browsers and image viewers play, written without
// ffmpeg. The file is a PNG whose IDAT holds the first frame (what a viewer
// without APNG support shows); each later frame is an fcTL chunk (size,
// delay) and fdAT chunks holding the same zlib data an ordinary PNG would.
#include <filesystem>
#include <string>
#include <vector>

namespace rsl {

class AnimatedPng {
public:
    // Every frame has this size and 3 (RGB) or 4 (RGBA, straight alpha) channels.
    AnimatedPng(int width, int height, int channels);

    // One frame of 8-bit pixels (tone_mapped_pixels: rows top to bottom,
    // channels interleaved), compressed now: only the compressed data is kept.
    void add_frame(const std::vector<unsigned char>& pixels);
    size_t frame_count() const { return frames_.size(); }

    // The file: every frame shown for `frame_seconds` (> 0), looping forever.
    // Throws rsl::Error without frames.
    std::string encode(double frame_seconds) const;

private:
    int width_, height_, channels_;
    std::string header_;               // the IHDR chunk's data
    std::vector<std::string> frames_;  // each frame's zlib stream (its PNG's IDAT data, joined)
};

// Writes `animation` to `path` atomically (write_file_atomically).
void write_animated_png(const std::filesystem::path& path, const AnimatedPng& animation, double frame_seconds);

}  // namespace rsl
