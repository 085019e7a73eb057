// Issue 43: a field file in the cache that is a FIFO, a link to /dev/zero
// or a 100 GB sparse file is refused at once (magic number first, then the
// size), not read whole or waited on.
#include <chrono>
#include <filesystem>

#include <catch2/catch.hpp>

#include "src/formats/file_reading.h"
#include "src/fields/field_file.h"
#include "tests/special_files.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

TEST_CASE("Field files that are not regular files, or too large, are refused at once", "[fields][bad-input][special-files]") {
    const fs::path dir = scratch_dir("field_special");
    const auto start = std::chrono::steady_clock::now();
    const fs::path fifo = make_fifo(dir / "svdf-fifo.rslf");
    {
        const FifoRelease release(fifo);
        CHECK(error_of([&] { read_svdf(fifo); }) == fifo.string() + ": is a FIFO (named pipe), not a regular file");
        CHECK(error_of([&] { read_field_header(fifo); }) == fifo.string() + ": is a FIFO (named pipe), not a regular file");
    }
    const fs::path zero = make_dev_zero_link(dir / "ovdf-zero.rslf");
    CHECK(error_of([&] { read_ovdf(zero); }) == zero.string() + ": is a character device, not a regular file");
    // 100 GB of hole: refused by its first eight bytes, then (with the magic) by its size.
    const fs::path foreign = make_sparse_file(dir / "svdf-foreign.rslf", uintmax_t(100) << 30);
    CHECK(error_of([&] { read_svdf(foreign); }) == foreign.string() + ": not an rsl field file (bad magic)");
    const fs::path huge = make_sparse_file(dir / "svdf-huge.rslf", uintmax_t(100) << 30, "RSLFIELD");
    CHECK(error_of([&] { read_svdf(huge); }) ==
          fmt::format("{}: is {} bytes; a field file may be at most {} bytes (4096 MiB)", huge.string(),
                      uintmax_t(100) << 30, kMaxFieldFileBytes));
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 3);
}
