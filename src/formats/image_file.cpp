// Image files: OpenEXR through the OpenEXR 3 library, Radiance RGBE through our
// own strict reader, PNG previews through stb_image_write.
#include "src/formats/image_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfEnvmapAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>

// The one translation unit that compiles stb_image_write (third-party code: its
// warnings are not ours).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#pragma GCC diagnostic pop

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"
#include "src/formats/exr_header.h"

namespace rsl {
namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------- OpenEXR

// An EXR file built in memory: OpenEXR's own file stream leaves its last
// buffered bytes unchecked, so the file is written by write_file_atomically.
class MemoryOStream : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (position_ + size_t(n) > bytes_.size()) bytes_.resize(position_ + size_t(n));
        std::memcpy(&bytes_[position_], c, size_t(n));
        position_ += size_t(n);
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t position) override { position_ = size_t(position); }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
    size_t position_ = 0;
};

std::string channel_names(const Imf::ChannelList& channels) {
    std::string names;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        if (!names.empty()) names += ",";
        names += it.name();
    }
    return names.empty() ? std::string("none") : names;
}

}  // namespace

void check_image_dimensions(const fs::path& path, long long width, long long height) {
    if (width <= 0 || height <= 0) throw_file_error(path, "image is empty ({}×{} pixels)", width, height);
    if (width > kMaxImagePixels || height > kMaxImagePixels || width * height > kMaxImagePixels)
        throw_file_error(path, "image size {}×{} is implausibly large (corrupt header?)", width, height);
}

void check_radiance(const fs::path& path, const Image& image) {
    const size_t count = image.pixels.size();
    for (size_t k = 0; k < count; ++k) {
        const float v = image.pixels[k];
        if (v >= 0.0f && v <= kMaxRadiance) continue;  // false for NaN
        const size_t pixel = k / image.channels;
        const int x = int(pixel % size_t(image.width)), y = int(pixel / size_t(image.width));
        const char* what = std::isnan(v)   ? "NaN"
                           : std::isinf(v) ? "infinite"
                           : v < 0.0f      ? "negative"
                                           : "implausibly large (above 1e15; corrupt file?)";
        throw_file_error(path, "{} value {} at pixel (x={}, y={}) channel {}", what, v, x, y,
                         "RGBA"[k % image.channels]);
    }
}

void check_writable_radiance(const fs::path& path, const Image& image) {
    for (size_t k = 0; k < image.pixels.size(); ++k) {
        const float v = image.pixels[k];
        if (std::abs(v) <= kMaxRadiance) continue;  // false for NaN
        const size_t pixel = k / image.channels;
        throw_file_error(path, "cannot write {} value {} at pixel (x={}, y={}) channel {}: rsl's readers refuse it "
                         "(finite, at most {:g}); nothing written",
                         std::isnan(v) ? "a NaN" : std::isinf(v) ? "an infinite" : "a too large", v,
                         pixel % size_t(image.width), pixel / size_t(image.width), "RGBA"[k % image.channels],
                         kMaxRadiance);
    }
}

Image read_exr(const fs::path& path) {
    const ExrWindowSize checked = check_exr_header(path);  // before OpenEXR allocates what the header claims
    Image image;
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imf::ChannelList& channels = header.channels();
        const bool rgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
        if (!rgb)
            throw_file_error(path, "has channels {{{}}}; only RGB or RGBA OpenEXR images are supported",
                             channel_names(channels));
        const bool alpha = channels.findChannel("A") != nullptr;
        const Imath::Box2i window = header.dataWindow();
        const long long width = (long long)window.max.x - window.min.x + 1;
        const long long height = (long long)window.max.y - window.min.y + 1;
        RSL_CHECK(width == checked.width && height == checked.height);  // the check read the header OpenEXR read
        image = Image(int(width), int(height), alpha ? 4 : 3);

        Imf::FrameBuffer frame;
        const size_t x_stride = sizeof(float) * image.channels;
        const size_t y_stride = x_stride * image.width;
        const char* names[] = {"R", "G", "B", "A"};
        for (int c = 0; c < image.channels; ++c)
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, &image.pixels[c], window, x_stride, y_stride));
        file.setFrameBuffer(frame);
        // OpenEXR converts half (or uint) channels to the FLOAT slices on read.
        file.readPixels(window.min.y, window.max.y);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_file_error(path, "not a readable OpenEXR image: {}", e.what());
    }
    check_radiance(path, image);
    return image;
}

EnvmapKind read_exr_envmap_kind(const fs::path& path) {
    check_exr_header(path);  // before OpenEXR allocates what the header claims
    try {
        Imf::InputFile file(path.c_str());
        if (!Imf::hasEnvmap(file.header())) return EnvmapKind::None;
        switch (Imf::envmap(file.header())) {
            case Imf::ENVMAP_LATLONG: return EnvmapKind::LatLong;
            case Imf::ENVMAP_CUBE: return EnvmapKind::Cube;
            default: throw_file_error(path, "unknown envmap attribute value {}", int(Imf::envmap(file.header())));
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_file_error(path, "not a readable OpenEXR image: {}", e.what());
    }
}

void write_exr(const fs::path& path, const Image& image, const ExrWriteOptions& options) {
    if (image.channels != 3 && image.channels != 4)
        throw_file_error(path, "cannot write an image with {} channels (need RGB or RGBA)", image.channels);
    check_image_dimensions(path, image.width, image.height);
    if (image.pixels.size() != size_t(image.width) * image.height * image.channels)
        throw_file_error(path, "pixel buffer holds {} values, expected {}×{}×{}", image.pixels.size(),
                         image.width, image.height, image.channels);
    check_writable_radiance(path, image);
    MemoryOStream stream;
    {
        try {
            Imf::Header header(image.width, image.height);
            header.compression() = Imf::ZIP_COMPRESSION;
            if (options.envmap != EnvmapKind::None)
                Imf::addEnvmap(header, options.envmap == EnvmapKind::Cube ? Imf::ENVMAP_CUBE : Imf::ENVMAP_LATLONG);
            const Imf::PixelType stored = options.half ? Imf::HALF : Imf::FLOAT;
            const char* names[] = {"R", "G", "B", "A"};
            for (int c = 0; c < image.channels; ++c) header.channels().insert(names[c], Imf::Channel(stored));
            // OpenEXR converts types on read but not on write: half files need half pixels.
            std::vector<Imath::half> halves;
            const char* base = (const char*)image.pixels.data();
            size_t value_size = sizeof(float);
            if (options.half) {
                halves.assign(image.pixels.begin(), image.pixels.end());
                base = (const char*)halves.data();
                value_size = sizeof(Imath::half);
            }
            Imf::FrameBuffer frame;
            const size_t x_stride = value_size * image.channels;
            const size_t y_stride = x_stride * image.width;
            for (int c = 0; c < image.channels; ++c)
                frame.insert(names[c], Imf::Slice(stored, (char*)base + c * value_size, x_stride, y_stride));
            Imf::OutputFile file(stream, header);  // its destructor writes the line offsets
            file.setFrameBuffer(frame);
            file.writePixels(image.height);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            throw_file_error(path, "cannot write OpenEXR image: {}", e.what());
        }
    }
    write_file_atomically(path, stream.bytes());
}

void write_exr(const fs::path& path, const Image& image) { write_exr(path, image, ExrWriteOptions{}); }

// ---------------------------------------------------------------- Radiance RGBE

namespace {

// A cursor over the file's bytes that names the file in every error.
class ByteReader {
public:
    ByteReader(const fs::path& path, std::string_view bytes) : path_(path), bytes_(bytes) {}

    bool at_end() const { return pos_ >= bytes_.size(); }
    size_t remaining() const { return bytes_.size() - pos_; }
    size_t position() const { return pos_; }

    // One header line without its '\n'; the header must end before the data.
    std::string_view line() {
        const size_t end = bytes_.find('\n', pos_);
        if (end == std::string_view::npos) throw_file_error(path_, "truncated header (no end of line)");
        std::string_view result = bytes_.substr(pos_, end - pos_);
        pos_ = end + 1;
        return result;
    }
    unsigned char byte() { return (unsigned char)bytes_[pos_++]; }
    const unsigned char* take(size_t count) {
        const unsigned char* p = (const unsigned char*)bytes_.data() + pos_;
        pos_ += count;
        return p;
    }

private:
    const fs::path& path_;
    std::string_view bytes_;
    size_t pos_ = 0;
};

// Radiance's colr_color: the +0.5 puts each value at the center of its mantissa bin.
inline void rgbe_to_float(const unsigned char* rgbe, float* out, float scale) {
    if (rgbe[3] == 0) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    const float f = std::ldexp(1.0f, int(rgbe[3]) - (128 + 8)) * scale;
    out[0] = (rgbe[0] + 0.5f) * f;
    out[1] = (rgbe[1] + 0.5f) * f;
    out[2] = (rgbe[2] + 0.5f) * f;
}

// New-style run-length scanline: four planes (R, G, B, E), each a sequence of
// runs (count > 128: one byte repeated count − 128 times) and literals
// (0 < count ≤ 128: count bytes follow).
void read_rle_scanline(const fs::path& path, ByteReader& in, int y, int width, unsigned char* rgbe) {
    for (int plane = 0; plane < 4; ++plane) {
        int x = 0;
        while (x < width) {
            if (in.at_end()) throw_file_error(path, "truncated data in scanline {} (plane {})", y, plane);
            int count = in.byte();
            const bool run = count > 128;
            if (run) count -= 128;
            if (count == 0 || x + count > width)
                throw_file_error(path, "bad run length {} at x={} in scanline {} (width {})", count, x, y, width);
            if (in.remaining() < size_t(run ? 1 : count))
                throw_file_error(path, "truncated data in scanline {} (plane {})", y, plane);
            if (run) {
                const unsigned char value = in.byte();
                for (int k = 0; k < count; ++k) rgbe[(x + k) * 4 + plane] = value;
            } else {
                const unsigned char* bytes = in.take(count);
                for (int k = 0; k < count; ++k) rgbe[(x + k) * 4 + plane] = bytes[k];
            }
            x += count;
        }
    }
}

struct RadianceHeader {
    int width = 0, height = 0;
    float exposure = 1.0f;  // product of EXPOSURE= lines: file value = radiance × exposure
};

RadianceHeader read_radiance_header(const fs::path& path, ByteReader& in) {
    const std::string_view magic = in.line();
    if (magic != "#?RADIANCE" && magic != "#?RGBE")
        throw_file_error(path, "not a Radiance file (first line must be #?RADIANCE or #?RGBE)");
    RadianceHeader header;
    for (;;) {
        const std::string_view line = in.line();
        if (line.empty()) break;  // a blank line ends the header
        if (line.starts_with("FORMAT=")) {
            if (line != "FORMAT=32-bit_rle_rgbe")
                throw_file_error(path, "unsupported pixel format '{}' (only 32-bit_rle_rgbe)", line.substr(7));
        } else if (line.starts_with("EXPOSURE=")) {
            const float e = std::strtof(std::string(line.substr(9)).c_str(), nullptr);
            if (!(e > 0.0f) || !std::isfinite(e)) throw_file_error(path, "bad header line '{}'", line);
            header.exposure *= e;
        }
    }
    const std::string resolution(in.line());
    char ysign = 0, xsign = 0, yaxis = 0, xaxis = 0;
    long long h = 0, w = 0;
    int consumed = 0;
    if (std::sscanf(resolution.c_str(), "%c%c %lld %c%c %lld%n", &ysign, &yaxis, &h, &xsign, &xaxis, &w,
                    &consumed) != 6 ||
        size_t(consumed) != resolution.size() || yaxis != 'Y' || xaxis != 'X' || ysign != '-' || xsign != '+')
        throw_file_error(path, "unsupported resolution line '{}' (only the standard orientation '-Y H +X W')",
                         resolution);
    check_image_dimensions(path, w, h);
    header.width = int(w);
    header.height = int(h);
    return header;
}

}  // namespace

static_assert(kMaxRadianceFileBytes >= 4 * uint64_t(kMaxImagePixels), "a flat file of the largest image must fit");

Image read_radiance_hdr(const fs::path& path) {
    const std::string bytes = read_bounded_file(path, kMaxRadianceFileBytes, "a Radiance HDR file", "#?",
                                                       "not a Radiance HDR file (no '#?' at its start)");
    ByteReader in(path, bytes);
    const RadianceHeader header = read_radiance_header(path, in);
    const int width = header.width;
    // The densest encoding, a run of 127 per two bytes in each of 4 channels
    // after a 4-byte scanline header, bounds what the file can hold: a header
    // that claims more is corrupt, and is refused before the image is allocated.
    const size_t min_scanline_bytes = width >= 8 && width < 32768 ? 4 + 8 * ((size_t(width) + 126) / 127) : 4 * size_t(width);
    if (in.remaining() / min_scanline_bytes < size_t(header.height))
        throw_file_error(path, "truncated or corrupt: {}×{} pixels need at least {} bytes of data, the file has {}",
                         width, header.height, min_scanline_bytes * header.height, in.remaining());
    Image image(width, header.height, 3);
    std::vector<unsigned char> rgbe(size_t(width) * 4);
    const float scale = 1.0f / header.exposure;
    for (int y = 0; y < header.height; ++y) {
        if (in.remaining() < 4) throw_file_error(path, "truncated data at scanline {} of {}", y, header.height);
        const unsigned char* peek = (const unsigned char*)bytes.data() + in.position();
        // RLE is only defined for widths 8..32767; a scanline starting 2,2 with
        // a clear high bit is run-length encoded, anything else is flat.
        const bool rle = width >= 8 && width < 32768 && peek[0] == 2 && peek[1] == 2 && peek[2] < 128;
        if (rle) {
            in.take(4);
            const int encoded_width = (peek[2] << 8) | peek[3];
            if (encoded_width != width)
                throw_file_error(path, "scanline {} has width {}, expected {}", y, encoded_width, width);
            read_rle_scanline(path, in, y, width, rgbe.data());
        } else {
            if (in.remaining() < rgbe.size())
                throw_file_error(path, "truncated data at scanline {} of {} (flat scanline)", y, header.height);
            std::memcpy(rgbe.data(), in.take(rgbe.size()), rgbe.size());
        }
        for (int x = 0; x < width; ++x) rgbe_to_float(&rgbe[size_t(x) * 4], image.at(x, y), scale);
    }
    check_radiance(path, image);
    return image;
}

// ---------------------------------------------------------------- dispatch

namespace {
enum class FileKind { Exr, Radiance, Unknown };

FileKind sniff(const fs::path& path) {
    const std::string prefix = read_file_prefix(path, 4);  // refuses a FIFO or a device before it blocks
    unsigned char magic[4] = {0, 0, 0, 0};
    const size_t got = prefix.size();
    std::memcpy(magic, prefix.data(), got);
    if (got == 0) throw_file_error(path, "file is empty");
    if (got == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01) return FileKind::Exr;
    if (got >= 2 && magic[0] == '#' && magic[1] == '?') return FileKind::Radiance;
    return FileKind::Unknown;
}

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}
}  // namespace

Image read_hdr_image(const fs::path& path) {
    const FileKind kind = sniff(path);
    const std::string ext = lower_extension(path);
    const bool exr_name = ext == ".exr";
    const bool radiance_name = ext == ".hdr" || ext == ".pic" || ext == ".rgbe";
    switch (kind) {
        case FileKind::Exr:
            if (!exr_name)
                throw_file_error(path, "mislabeled: the extension '{}' disagrees with the content (OpenEXR)", ext);
            return read_exr(path);
        case FileKind::Radiance:
            if (!radiance_name)
                throw_file_error(path, "mislabeled: the extension '{}' disagrees with the content (Radiance .hdr)",
                                 ext);
            return read_radiance_hdr(path);
        case FileKind::Unknown: break;
    }
    throw_file_error(path, "not an OpenEXR or Radiance HDR image (unrecognized magic number)");
}

// ---------------------------------------------------------------- PNG previews

unsigned char linear_to_srgb8(float v) {
    if (!(v > 0.0f)) return 0;  // also maps NaN to black
    if (v >= 1.0f) return 255;
    const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return (unsigned char)std::lround(s * 255.0f);
}

namespace {
// Scale that maps the 99th luminance percentile to 0.9 (1 when the image is black).
float auto_exposure_scale(const Image& image) {
    std::vector<float> lum(size_t(image.width) * image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) lum[size_t(y) * image.width + x] = luminance(image.rgb(x, y));
    const size_t k = size_t(0.99 * double(lum.size() - 1));
    std::nth_element(lum.begin(), lum.begin() + k, lum.end());
    return lum[k] > 0.0f ? 0.9f / lum[k] : 1.0f;
}
}  // namespace

float auto_exposure_stops(const Image& image) { return std::log2(auto_exposure_scale(image)); }

std::vector<unsigned char> tone_mapped_pixels(const Image& image, const ToneMap& tone) {
    RSL_CHECK(image.channels == 3 || image.channels == 4);
    float scale = std::exp2(tone.exposure);
    if (tone.auto_exposure) scale *= auto_exposure_scale(image);
    const int c = image.channels;
    std::vector<unsigned char> bytes(size_t(image.width) * image.height * c);
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
        const float* px = &image.pixels[p * c];
        // EXR colour is premultiplied by alpha; PNG stores straight alpha.
        const float alpha = c == 4 ? std::clamp(px[3], 0.0f, 1.0f) : 1.0f;
        const float unpremultiply = alpha > 0.0f ? 1.0f / alpha : 0.0f;
        for (int k = 0; k < 3; ++k) bytes[p * c + k] = linear_to_srgb8(px[k] * scale * (c == 4 ? unpremultiply : 1.0f));
        if (c == 4) bytes[p * c + 3] = (unsigned char)std::lround(alpha * 255.0f);
    }
    return bytes;
}

void write_png(const fs::path& path, const Image& image, const ToneMap& tone) {
    if (image.channels != 3 && image.channels != 4)
        throw_file_error(path, "cannot write an image with {} channels as PNG", image.channels);
    check_image_dimensions(path, image.width, image.height);
    const std::vector<unsigned char> bytes = tone_mapped_pixels(image, tone);
    write_file_atomically(path, encode_png(bytes.data(), image.width, image.height, image.channels));
}

std::string encode_png(const unsigned char* pixels, int width, int height, int channels) {
    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels, width * channels))
        throw_error("cannot encode a {}×{} PNG of {} channels", width, height, channels);
    return png;
}

void write_exr_and_png(const fs::path& exr_path, const Image& image, const ToneMap& tone) {
    fs::path png_path = exr_path;
    png_path.replace_extension(".png");
    write_exr(exr_path, image);
    write_png(png_path, image, tone);
}

}  // namespace rsl
