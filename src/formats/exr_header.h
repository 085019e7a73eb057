#pragma once
// A check of an OpenEXR file's headers against the file's own size, before
// the OpenEXR library reads it. The library allocates what a header says
// before it finds the file too short: a string or unknown attribute of 2 GB
// in a 500-byte file (fuzz_exr found one), an offset table for 2^31 scan
// lines, line buffers for a 2^30-pixel-wide window. Real files pass; a
// corrupt header is refused naming the file.
#include <filesystem>

namespace rsl {

// Every header's attributes are well formed and fit in the file (a known
// type's size is the size OpenEXR reads for it); the first part's data
// window holds at most kMaxImagePixels (src/formats/image_file.h) and no more
// samples than its compression can pack into the file, and its offset table
// fits in the file. Throws rsl::Error "<path>: not a readable OpenEXR image:
// ... (corrupt header?)". Returns the data window's size.
struct ExrWindowSize {
    long long width = 0, height = 0;
};
ExrWindowSize check_exr_header(const std::filesystem::path& path);

}  // namespace rsl
