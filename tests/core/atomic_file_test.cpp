#include <filesystem>

#include <catch2/catch.hpp>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "tests/test_support.h"

using namespace rsl;
namespace fs = std::filesystem;

TEST_CASE("atomic write leaves no partial file on failure", "[atomic]") {
    const fs::path dir = test::scratch_dir("atomic") / "created";  // write_atomically creates it
    fs::path target = dir / "out.bin";
    write_file_atomically(target, "first");
    CHECK(read_file(target) == "first");
    CHECK_THROWS_AS(write_atomically(target,
                                     [](const fs::path& tmp) {
                                         write_file_atomically(tmp, "half");
                                         throw Error("writer failed");
                                     }),
                    Error);
    CHECK(read_file(target) == "first");  // the old contents survive
    int files = 0;
    for (auto& e : fs::directory_iterator(dir)) { (void)e; ++files; }
    CHECK(files == 1);  // no temporary left behind
    CHECK_THROWS_WITH(read_file(dir / "missing"), Catch::Contains("missing"));
}
