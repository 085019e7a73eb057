#pragma once
// Fault tests of the `rsl` commands that write files (bake, truth, render):
// the command is killed (SIGKILL) at several moments; whatever stands under
// a final name must then be whole, and a rerun must complete and leave no
// temporary (".NAME.rsl-tmp-HOST-PID-RANDOM.EXT", src/core/atomic_file.h) behind.
#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "src/core/atomic_file.h"
#include "src/formats/image_file.h"
#include "tests/test_support.h"

namespace rsl::test {

// The temporaries write_atomically leaves in `dir` (names ".STEM.rsl-tmp-...").
inline std::vector<std::filesystem::path> temporaries_in(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> found;
    if (!std::filesystem::exists(dir)) return found;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name[0] == '.' && name.find(".rsl-tmp-") != std::string::npos) found.push_back(entry.path());
    }
    return found;
}

// A temporary of `target` as a writer that died mid-write would leave it
// (its process id is one that has exited), so that a rerun's sweep is tested
// even when no kill happened to land inside a write.
inline std::filesystem::path plant_stale_temporary(const std::filesystem::path& target) {
    const pid_t child = ::fork();
    if (child == 0) std::_Exit(0);
    ::waitpid(child, nullptr, 0);
    const std::filesystem::path tmp = temporary_path(target, long(child));
    write_text(tmp, "half written");
    return tmp;
}

struct KilledRuns {
    int killed = 0;  // runs that were killed (not ended first)
};

// Runs `command` once per delay, killed (SIGKILL) after that many seconds
// unless it ends first, with `outputs` removed before each run; after each,
// check_whole(path) is called for every output that exists (it must fail
// the test when the file is partial).
inline KilledRuns run_killed(const std::string& command, const std::vector<double>& delays,
                             const std::vector<std::filesystem::path>& outputs,
                             const std::function<void(const std::filesystem::path&)>& check_whole) {
    KilledRuns runs;
    for (const double delay : delays) {
        for (const auto& output : outputs) std::filesystem::remove(output);
        // --foreground: timeout kills only the command and reaps it. Without
        // it, timeout KILLs its whole process group, itself included, and the
        // orphaned command lives on as a zombie until init reaps it, so a
        // rerun may still see it alive and rightly keep its temporaries.
        const auto [status, text] = run_command(fmt::format("timeout --foreground -s KILL {:.3f} {}", delay, command));
        INFO("killed after " << delay << " s, status " << status << "\n" << text);
        if (status == 128 + 9) ++runs.killed;  // timeout's status for a child it killed
        for (const auto& output : outputs)
            if (std::filesystem::exists(output)) {
                INFO("under its final name: " << output);
                check_whole(output);
            }
    }
    return runs;
}

// Runs `command` and kills it (SIGKILL) the moment a new temporary shows in
// `watched`, so that the kill lands inside a write whatever the machine's
// speed (the timed kills of run_killed depend on it: a sanitizer build or a
// loaded machine moves the write). True when the kill left the temporary, a
// write cut for certain; false when the command ended or finished its write
// first.
inline bool killed_inside_a_write(const std::string& command, const std::filesystem::path& watched) {
    // A run sweeps dead runs' temporaries before it writes: look for a new name, not a larger count.
    const std::vector<std::filesystem::path> before = temporaries_in(watched);
    const auto new_temporary = [&] {
        for (const auto& path : temporaries_in(watched))
            if (std::find(before.begin(), before.end(), path) == before.end()) return true;
        return false;
    };
    const std::string shell_command = "exec " + command;
    const pid_t child = ::fork();
    if (child == 0) {
        const int null_fd = ::open("/dev/null", O_WRONLY);
        ::dup2(null_fd, 1), ::dup2(null_fd, 2);
        ::execl("/bin/sh", "sh", "-c", shell_command.c_str(), static_cast<char*>(nullptr));
        std::_Exit(127);
    }
    int status = 0;
    while (!new_temporary()) {
        if (::waitpid(child, &status, WNOHANG) == child) return false;
        ::usleep(100);
    }
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
    return new_temporary();
}

// The scene the truth and render kill tests run: an (n + 1)²-vertex ground
// and a unit box under a white sky, seen by a 1600×1200 camera so that the
// EXR write takes a good part of a run; `precompute` is the scene file's
// precompute section (JSON, or empty for the defaults).
inline void write_killable_scene(const std::filesystem::path& dir, int n, const std::string& precompute = "") {
    write_text(dir / "ground.obj", grid_obj(n, 2.0));
    write_text(dir / "box.obj", kUnitBoxObj);
    Image white(64, 32, 3);
    std::fill(white.pixels.begin(), white.pixels.end(), 1.0f);
    write_exr(dir / "white.exr", white);
    write_text(dir / "scene.json", R"({
  "name": "killed",
  "parts": [ { "name": "ground", "obj": "ground.obj" }, { "name": "box", "obj": "box.obj" } ],
  "environment": { "file": "white.exr", "resolution": 16 },
  "subdivision": false,
  "camera": { "position": [0, 3, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_degrees": 50,
              "width": 1600, "height": 1200 })" + (precompute.empty() ? "" : ",\n  \"precompute\": " + precompute) +
                                         "\n}\n");
}

// Whether `bytes` is a whole PNG: the signature, and the IEND chunk last.
inline bool is_whole_png(const std::string& bytes) {
    const std::string signature = "\x89PNG\r\n\x1a\n", end = std::string("IEND\xae\x42\x60\x82", 8);
    return bytes.size() > signature.size() + end.size() && bytes.compare(0, signature.size(), signature) == 0 &&
           bytes.compare(bytes.size() - end.size(), end.size(), end) == 0;
}

// The wall time of one uninterrupted run of `command` (status 0 required).
inline double timed_run(const std::string& command) {
    const auto start = std::chrono::steady_clock::now();
    const auto [status, text] = run_command(command);
    INFO(text);
    REQUIRE(status == 0);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rsl::test
