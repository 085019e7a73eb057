#include <csignal>
#include <filesystem>
#include <fstream>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

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

TEST_CASE("a writer killed mid-write leaves no final file, and the next write sweeps its temporary", "[atomic][fault]") {
    const fs::path dir = test::scratch_dir("atomic_killed");
    const fs::path target = dir / "field.rslf";
    const auto temporaries = [&] {
        std::vector<fs::path> found;
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.path().filename().string().rfind(".field.rsl-tmp-", 0) == 0) found.push_back(entry.path());
        return found;
    };
    // A live process's temporary (pid 1 always runs) must survive the sweep.
    const fs::path live = temporary_path(target, 1);
    write_file_atomically(dir / "unrelated.txt", "x");
    { std::ofstream(live) << "in progress"; }
    for (int trial = 0; trial < 3; ++trial) {
        const pid_t child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {
            write_atomically(target, [](const fs::path& tmp) {
                std::ofstream out(tmp, std::ios::binary);
                out << std::string(1 << 16, 'a') << std::flush;
                for (;;) ::pause();  // killed here, half written
            });
            std::_Exit(0);
        }
        // Wait for the child's temporary, then kill it at once.
        for (int wait = 0; wait < 2000 && temporaries().size() < 2; ++wait) ::usleep(1000);
        ::kill(child, SIGKILL);
        int status = 0;
        ::waitpid(child, &status, 0);
        CHECK(WIFSIGNALED(status));
        CHECK(temporaries().size() == 2);  // the dead child's and the live one
        CHECK(!fs::exists(target));
    }
    // The rerun completes and removes what the dead writers left, not the live one's.
    // (Each trial's dead temporary is swept by the next trial's child.)
    write_file_atomically(target, "complete");
    CHECK(read_file(target) == "complete");
    const auto left = temporaries();
    REQUIRE(left.size() == 1);
    CHECK(left[0] == live);
    fs::remove_all(dir);
}

TEST_CASE("check_outputs_apart names an output that is an input by any path, link or hard link", "[atomic][issue-56]") {
    const fs::path dir = test::scratch_dir("outputs_apart");
    write_file_atomically(dir / "in.exr", "input");
    fs::create_hard_link(dir / "in.exr", dir / "hard.exr");
    fs::create_symlink(dir / "in.exr", dir / "soft.exr");
    const std::vector<fs::path> inputs = {dir / "in.exr"};
    for (const fs::path& output : {dir / "in.exr", dir / "hard.exr", dir / "soft.exr", dir / "." / "in.exr",
                                   dir / "absent" / ".." / "in.exr"})
        CHECK_THROWS_WITH(check_outputs_apart({output}, inputs),
                          Catch::StartsWith(output.string() + ": this output is the input " + (dir / "in.exr").string()));
    CHECK_NOTHROW(check_outputs_apart({dir / "out.exr", dir / "new" / "out.exr", {}}, inputs));
    CHECK_THROWS_WITH(check_outputs_apart({dir / "out.exr", dir / "new" / ".." / "out.exr"}, inputs),
                      Catch::Contains("two outputs are this one file"));
    CHECK(read_file(dir / "in.exr") == "input");
    fs::remove_all(dir);
}
