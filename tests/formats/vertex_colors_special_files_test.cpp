// Issue 43: an .rslv path that is a FIFO, a device or a huge sparse file is
// refused at once, naming it and what it is.
#include <chrono>
#include <filesystem>

#include <catch2/catch.hpp>

#include "src/formats/file_reading.h"
#include "src/formats/vertex_colors.h"
#include "tests/special_files.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

TEST_CASE(".rslv readers refuse FIFOs, devices and oversized files at once", "[frame][bad-input][special-files]") {
    const fs::path dir = scratch_dir("rslv_special");
    const auto start = std::chrono::steady_clock::now();
    const fs::path fifo = make_fifo(dir / "colors.rslv");
    {
        const FifoRelease release(fifo);
        CHECK(error_of([&] { read_vertex_colors(fifo); }) == fifo.string() + ": is a FIFO (named pipe), not a regular file");
    }
    CHECK(error_of([&] { read_vertex_colors(make_directory(dir / "folder.rslv")); }) ==
          (dir / "folder.rslv").string() + ": is a directory, not a regular file");
    const fs::path zero = make_dev_zero_link(dir / "zero.rslv");
    CHECK(error_of([&] { read_vertex_colors(zero); }) == zero.string() + ": is a character device, not a regular file");
    const fs::path huge = make_sparse_file(dir / "huge.rslv", uintmax_t(100) << 30, std::string("RSLVTXC\0", 8));
    CHECK(error_of([&] { read_vertex_colors(huge); }).find("a vertex-colour file may be at most") != std::string::npos);
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 3);
}
