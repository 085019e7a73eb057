#pragma once
// Image files: OpenEXR (read/write), Radiance .hdr (read), tone-mapped PNG
// (write), of the float images of src/core/image.h. Readers validate
// everything and throw rsl::Error naming the file; writers are atomic.
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/image.h"

namespace rsl {

// Reads .exr or .hdr by content (magic number), not by extension; a file whose
// extension disagrees with its content is refused as mislabeled. Rejects NaN,
// Inf and negative radiance with the pixel position.
Image read_hdr_image(const std::filesystem::path& path);
Image read_exr(const std::filesystem::path& path);
Image read_radiance_hdr(const std::filesystem::path& path);

void write_exr(const std::filesystem::path& path, const Image& image);

// OpenEXR's standard `envmap` attribute: how a file's pixels map to directions.
enum class EnvmapKind { None, LatLong, Cube };

struct ExrWriteOptions {
    bool half = false;                    // store 16-bit half instead of 32-bit float
    EnvmapKind envmap = EnvmapKind::None;  // written as the `envmap` attribute when not None
};
void write_exr(const std::filesystem::path& path, const Image& image, const ExrWriteOptions& options);
// The `envmap` attribute of an EXR file's header (None when absent).
EnvmapKind read_exr_envmap_kind(const std::filesystem::path& path);

// The most pixels an image file may hold: larger ones are certainly a
// corrupt header, not a real map (a 32768 × 8192 probe has 2^28).
inline constexpr long long kMaxImagePixels = 1LL << 28;
// Throws rsl::Error naming `path` unless 1 ≤ width, height and
// width × height ≤ kMaxImagePixels.
void check_image_dimensions(const std::filesystem::path& path, long long width, long long height);

// The largest radiance an input image may hold. Real probes with an
// unclipped sun stay below 1e10 (photometric units included); a value far
// beyond is a corrupt file (flipped exponent bits), and squares and sums of
// such values overflow the light fit's float arithmetic.
inline constexpr float kMaxRadiance = 1e15f;

// Throws rsl::Error naming `path` and the first pixel (x, y, channel) whose
// value is NaN, infinite, negative or above kMaxRadiance. Readers call it;
// writers may too.
void check_radiance(const std::filesystem::path& path, const Image& image);

// Throws rsl::Error naming `path` and the first pixel whose value is NaN,
// infinite or beyond ±kMaxRadiance: write_exr calls it, so that rsl never
// writes an image its own readers refuse.
void check_writable_radiance(const std::filesystem::path& path, const Image& image);

struct ToneMap {
    float exposure = 0.0f;  // stops: pixel × 2^exposure
    bool auto_exposure = false;  // scale so the 99th luminance percentile maps to ~0.9
};
// The tone-mapped 8-bit sRGB pixels write_png stores (RGB, or straight RGBA
// when the image has alpha), rows top to bottom.
std::vector<unsigned char> tone_mapped_pixels(const Image& image, const ToneMap& tone);
// The exposure in stops that ToneMap::auto_exposure picks for `image`: a
// sequence tone-mapped with its first frame's keeps one brightness.
float auto_exposure_stops(const Image& image);
// Tone-mapped 8-bit sRGB PNG (RGB, or RGBA when the image has alpha).
void write_png(const std::filesystem::path& path, const Image& image, const ToneMap& tone = {});
// The PNG file of 8-bit pixels (rows top to bottom, `channels` interleaved),
// to write with write_file_atomically: stb's own file writer ignores failed writes.
std::string encode_png(const unsigned char* pixels, int width, int height, int channels);
// 8-bit sRGB encoding of a linear value in [0, 1].
unsigned char linear_to_srgb8(float v);

// Writes PATH (.exr) and its PNG preview beside it (same stem, .png).
void write_exr_and_png(const std::filesystem::path& exr_path, const Image& image, const ToneMap& tone = {});

}  // namespace rsl
