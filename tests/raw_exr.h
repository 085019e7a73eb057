#pragma once
// An EXR written straight through OpenEXR, bypassing write_exr's checks: the
// bad files (NaN, Inf, negative radiance) that only another program writes,
// for the readers' tests.
#include <filesystem>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include "src/formats/image_file.h"

namespace rsl::test {

inline void write_unchecked_exr(const std::filesystem::path& path, const Image& image) {
    Imf::Header header(image.width, image.height);
    const char* names[] = {"R", "G", "B", "A"};
    Imf::FrameBuffer frame;
    const size_t x_stride = sizeof(float) * image.channels, y_stride = x_stride * image.width;
    for (int c = 0; c < image.channels; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)(image.pixels.data() + c), x_stride, y_stride));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
}

}  // namespace rsl::test
