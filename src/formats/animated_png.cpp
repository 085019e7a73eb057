#include "src/formats/animated_png.h"

#include <array>
#include <cmath>
#include <cstdint>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"

namespace rsl {
namespace {

constexpr std::string_view kPngSignature{"\x89PNG\r\n\x1a\n", 8};

uint32_t crc32(std::string_view bytes) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t n = 0; n < 256; ++n) {
            uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    uint32_t c = 0xffffffffu;
    for (const char byte : bytes) c = table[(c ^ uint8_t(byte)) & 0xff] ^ (c >> 8);
    return c ^ 0xffffffffu;
}

void put_u32(std::string& out, uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) out += char((value >> shift) & 0xff);
}
void put_u16(std::string& out, uint32_t value) {
    out += char((value >> 8) & 0xff);
    out += char(value & 0xff);
}
uint32_t get_u32(std::string_view bytes, size_t at) {
    uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value = value << 8 | uint8_t(bytes[at + i]);
    return value;
}

void put_chunk(std::string& out, std::string_view type, std::string_view data) {
    if (data.size() > 0x7fffffffu) throw_error("an animated PNG frame of {} bytes is past PNG's chunk limit", data.size());
    put_u32(out, uint32_t(data.size()));
    std::string typed(type);
    typed += data;
    out += typed;
    put_u32(out, crc32(typed));
}

// A PNG stb wrote, split into its IHDR data and its IDAT data joined.
void split_png(const std::string& png, std::string& header, std::string& data) {
    RSL_CHECK(png.compare(0, kPngSignature.size(), kPngSignature) == 0);
    for (size_t at = kPngSignature.size(); at + 12 <= png.size();) {
        const uint32_t length = get_u32(png, at);
        const std::string_view type(png.data() + at + 4, 4);
        RSL_CHECK(at + 12 + length <= png.size());
        const std::string_view body(png.data() + at + 8, length);
        if (type == "IHDR") header = body;
        if (type == "IDAT") data += body;
        at += 12 + length;
    }
}

// Delay as the fcTL fraction numerator / denominator (16 bits each).
std::pair<uint32_t, uint32_t> delay_fraction(double seconds) {
    if (seconds * 1000.0 <= 65535.0) return {uint32_t(std::max(1.0, std::round(seconds * 1000.0))), 1000};
    return {uint32_t(std::min(65535.0, std::round(seconds))), 1};
}

}  // namespace

AnimatedPng::AnimatedPng(int width, int height, int channels) : width_(width), height_(height), channels_(channels) {
    RSL_CHECK(channels == 3 || channels == 4);
    RSL_CHECK(width > 0 && height > 0);
}

void AnimatedPng::add_frame(const std::vector<unsigned char>& pixels) {
    RSL_CHECK_EQ(pixels.size(), size_t(width_) * height_ * channels_);
    std::string header, data;
    split_png(encode_png(pixels.data(), width_, height_, channels_), header, data);
    if (header_.empty()) header_ = header;
    RSL_CHECK(header == header_);
    frames_.push_back(std::move(data));
}

std::string AnimatedPng::encode(double frame_seconds) const {
    if (frames_.empty()) throw_error("an animated PNG needs at least one frame");
    RSL_CHECK(frame_seconds > 0);
    const auto [delay_num, delay_den] = delay_fraction(frame_seconds);
    std::string out(kPngSignature);
    put_chunk(out, "IHDR", header_);
    std::string actl;
    put_u32(actl, uint32_t(frames_.size()));
    put_u32(actl, 0);  // plays: 0 loops forever
    put_chunk(out, "acTL", actl);
    uint32_t sequence = 0;
    for (size_t f = 0; f < frames_.size(); ++f) {
        std::string fctl;
        put_u32(fctl, sequence++);
        put_u32(fctl, uint32_t(width_));
        put_u32(fctl, uint32_t(height_));
        put_u32(fctl, 0);  // x offset
        put_u32(fctl, 0);  // y offset
        put_u16(fctl, delay_num);
        put_u16(fctl, delay_den);
        fctl += char(0);  // dispose: none (the next frame covers the whole canvas)
        fctl += char(0);  // blend: source (a frame's alpha replaces, not composites over, the last)
        put_chunk(out, "fcTL", fctl);
        if (f == 0) {
            put_chunk(out, "IDAT", frames_[f]);
        } else {
            std::string fdat;
            put_u32(fdat, sequence++);
            fdat += frames_[f];
            put_chunk(out, "fdAT", fdat);
        }
    }
    put_chunk(out, "IEND", "");
    return out;
}

void write_animated_png(const std::filesystem::path& path, const AnimatedPng& animation, double frame_seconds) {
    write_file_atomically(path, animation.encode(frame_seconds));
}

}  // namespace rsl
