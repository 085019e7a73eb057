// The OpenEXR header check of exr_header.h. The layout is that of the
// OpenEXR File Layout document (openexr.com): the magic number, a version
// field whose bit 9 marks a tiled file and bit 12 a multi-part one, then per
// part a header of attributes (name\0 type\0 int32 size, value) ended by an
// empty name; a multi-part file ends its headers with an empty one.
#include "src/formats/exr_header.h"

#include <cstdint>
#include <fstream>
#include <map>
#include <string>

#include "src/core/error.h"
#include "src/formats/file_reading.h"
#include "src/formats/image_file.h"

namespace rsl {
namespace fs = std::filesystem;

namespace {

// The bytes OpenEXR reads for an attribute type whose value has a fixed size
// (it reads them whatever size the attribute declares; -1: not such a type).
int fixed_value_size(const std::string& type) {
    static const std::map<std::string, int> sizes = {
        {"box2f", 16},   {"box2i", 16},          {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
        {"double", 8},   {"envmap", 1},          {"float", 4},           {"int", 4},         {"keycode", 28},
        {"lineOrder", 1}, {"m33d", 72},          {"m33f", 36},           {"m44d", 128},      {"m44f", 64},
        {"rational", 8}, {"tiledesc", 9},        {"timecode", 8},        {"v2d", 16},        {"v2f", 8},
        {"v2i", 8},      {"v3d", 24},            {"v3f", 12},            {"v3i", 12}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? -1 : it->second;
}

// Scan lines per chunk of each compression (Imf::Compression's numbering);
// unknown ones count as the largest.
int lines_per_chunk(uint8_t compression) {
    if (compression <= 2) return 1;                          // none, RLE, ZIPS
    if (compression == 3 || compression == 5) return 16;     // ZIP, PXR24
    if (compression == 4 || (compression >= 6 && compression <= 8)) return 32;  // PIZ, B44, B44A, DWAA
    return 256;                                              // DWAB
}

// What the checks need from the first part's header.
struct PartHeader {
    bool has_window = false, tiled = false;
    int32_t window[4] = {0, 0, 0, 0};  // xMin, yMin, xMax, yMax
    int channels = 0;
    uint8_t compression = 0;
    int envmap = -1;  // 0 lat-long, 1 cube
    uint32_t tile_width = 0, tile_height = 0;
};

class HeaderScanner {
public:
    explicit HeaderScanner(const fs::path& path)
        : path_(path), in_(path, std::ios::binary), size_(fs::file_size(path)) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw_file_error(path_, "not a readable OpenEXR image: {} (corrupt header?)", what);
    }

    // The headers; returns the first part's.
    PartHeader scan() {
        uint32_t magic = get<uint32_t>("the magic number"), version = get<uint32_t>("the version");
        if (magic != 20000630) fail("bad magic number");
        const bool multipart = version & 0x1000;
        PartHeader first;
        first.tiled = version & 0x200;
        attributes(first);
        while (multipart && peek() != 0) {
            PartHeader other;
            attributes(other);
        }
        return first;
    }

    uintmax_t file_size() const { return size_; }

private:
    uintmax_t left() const { return size_ - at_; }
    void read(void* out, uintmax_t count, const char* what) {
        if (count > left() || !in_.read(static_cast<char*>(out), std::streamsize(count)))
            fail(fmt::format("the file ends inside {}", what));
        at_ += count;
    }
    template <typename T>
    T get(const char* what) {
        T value;
        read(&value, sizeof(T), what);
        return value;
    }
    void skip(uintmax_t count, const char* what) {
        if (count > left()) fail(fmt::format("the file ends inside {}", what));
        in_.seekg(std::streamoff(count), std::ios::cur);
        at_ += count;
    }
    int peek() {
        if (left() == 0) fail("the file ends before the end of its headers");
        return in_.peek();
    }
    // A name: up to 255 bytes and a \0.
    std::string name(const char* what) {
        std::string s;
        for (char c = get<char>(what); c != '\0'; c = get<char>(what)) {
            if (s.size() == 255) fail(fmt::format("{} longer than 255 bytes", what));
            s += c;
        }
        return s;
    }

    void attributes(PartHeader& part) {
        for (std::string name = this->name("an attribute name"); !name.empty(); name = this->name("an attribute name")) {
            const std::string type = this->name("an attribute type");
            const int32_t size = get<int32_t>("an attribute size");
            if (size < 0 || uintmax_t(size) > left())
                fail(fmt::format("attribute '{}' ({}) claims {} bytes, the file has {} left", name, type, size, left()));
            const uintmax_t end = at_ + uintmax_t(size);
            const int fixed = fixed_value_size(type);
            if (fixed >= 0 && size != fixed)
                fail(fmt::format("attribute '{}' ({}) has {} bytes, the type has {}", name, type, size, fixed));
            if (type == "chlist") {
                // Read by its structure: names (and 16 bytes each) up to an empty name.
                for (std::string channel = this->name("a channel name"); !channel.empty();
                     channel = this->name("a channel name")) {
                    skip(16, "a channel");
                    ++part.channels;
                }
            } else if (type == "preview") {
                const uint64_t w = get<uint32_t>("a preview"), h = get<uint32_t>("a preview");
                if (w * h * 4 + 8 != uint64_t(size))
                    fail(fmt::format("a {}×{} preview in an attribute of {} bytes", w, h, size));
            } else if (type == "stringvector") {
                while (at_ < end) {
                    const int32_t length = get<int32_t>("a string vector");
                    if (length < 0 || at_ + uintmax_t(length) > end)
                        fail(fmt::format("attribute '{}' holds a string of {} bytes", name, length));
                    skip(uintmax_t(length), "a string vector");
                }
            } else if (name == "dataWindow" && type == "box2i") {
                for (int32_t& v : part.window) v = get<int32_t>("the data window");
                part.has_window = true;
            } else if (name == "compression" && type == "compression") {
                part.compression = get<uint8_t>("the compression");
            } else if (name == "envmap" && type == "envmap") {
                part.envmap = get<uint8_t>("the envmap attribute");
            } else if (name == "tiles" && type == "tiledesc") {
                part.tile_width = get<uint32_t>("the tile description");
                part.tile_height = get<uint32_t>("the tile description");
                part.tiled = true;
            }
            if (at_ > end) fail(fmt::format("attribute '{}' ({}) holds more than its {} bytes", name, type, size));
            skip(end - at_, "an attribute");
        }
    }

    const fs::path& path_;
    std::ifstream in_;
    uintmax_t size_ = 0, at_ = 0;
};

}  // namespace

ExrWindowSize check_exr_header(const fs::path& path) {
    check_regular_file(path);  // the scanner's ifstream would block on a FIFO
    HeaderScanner scanner(path);
    const PartHeader h = scanner.scan();
    if (!h.has_window) scanner.fail("no dataWindow attribute");
    const long long width = (long long)h.window[2] - h.window[0] + 1, height = (long long)h.window[3] - h.window[1] + 1;
    check_image_dimensions(path, width, height);
    // A file that declares a layout must have its shape.
    if (h.envmap == 0 && width != 2 * height)
        scanner.fail(fmt::format("declares a latitude-longitude (2:1) map, but its data window is {}×{}", width, height));
    if (h.envmap == 1 && height != 6 * width)
        scanner.fail(fmt::format("declares a cube (1:6 strip) map, but its data window is {}×{}", width, height));
    // No compression packs more than about 1,032 samples of 2 bytes (deflate's
    // limit) into one byte of the file.
    const uintmax_t samples = uintmax_t(width) * uintmax_t(height) * uintmax_t(std::max(h.channels, 1));
    if (samples * 2 / 1032 > scanner.file_size())
        scanner.fail(fmt::format("its data window {}×{} needs more data than the file's {} bytes can hold", width,
                                 height, scanner.file_size()));
    // The offset table (8 bytes a chunk, the first level's chunks at least) is in the file.
    if (h.tiled && (h.tile_width == 0 || h.tile_height == 0)) scanner.fail("a tiled file without a tile size");
    const uintmax_t chunks =
        h.tiled ? ((uintmax_t(width) + h.tile_width - 1) / h.tile_width) * ((uintmax_t(height) + h.tile_height - 1) / h.tile_height)
                : (uintmax_t(height) + lines_per_chunk(h.compression) - 1) / lines_per_chunk(h.compression);
    if (chunks > scanner.file_size() / 8)
        scanner.fail(fmt::format("its offset table of {} chunks does not fit in the file's {} bytes", chunks,
                                 scanner.file_size()));
    return {width, height};
}

}  // namespace rsl
