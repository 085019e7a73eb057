#pragma once
// Helpers shared by the test suites: per-process scratch folders, small file
// helpers, the message of an expected rsl::Error, running the `rsl` program,
// and capture of rsl::warn() output.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "src/core/error.h"

namespace rsl::test {

// The folder `name` (created if needed) inside this process's scratch folder.
// ctest runs test cases as separate processes and several builds may run the
// suite at once, so the scratch folder carries the process id; it is removed
// when the test program exits. Test cases use names of their own.
inline std::filesystem::path scratch_dir(const std::string& name) {
    static const struct Scratch {
        std::filesystem::path dir = std::filesystem::temp_directory_path() / fmt::format("rsl_test_{}", ::getpid());
        ~Scratch() {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    } scratch;
    const std::filesystem::path dir = scratch.dir / name;
    std::filesystem::create_directories(dir);
    return dir;
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

inline std::string read_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A unit box standing on y = 0 (quads, fan-triangulated by the reader).
inline constexpr const char* kUnitBoxObj =
    "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 1 -0.5\nv -0.5 1 -0.5\n"
    "v -0.5 0 0.5\nv 0.5 0 0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\nf 1 2 6 5\n";

// An OBJ sheet at y = 0 of (n + 1)² vertices over [−half, half]², 2n²
// triangles facing +Y: a mesh with many vertices in a few lines.
inline std::string grid_obj(int n, double half) {
    std::string obj;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) obj += fmt::format("v {} 0 {}\n", -half + 2 * half * i / n, -half + 2 * half * j / n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
            obj += fmt::format("f {} {} {}\nf {} {} {}\n", a, c, b, b, c, d);
        }
    return obj;
}

// The message of the rsl::Error that f() throws; empty when it throws none.
template <typename F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// Runs a shell command; returns its exit status (-1 when it did not run or
// was killed) and its stdout and stderr together.
inline std::pair<int, std::string> run_command(const std::string& command) {
    std::string output;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return {-1, "popen failed: " + command};
    char buffer[4096];
    while (std::fgets(buffer, sizeof(buffer), pipe)) output += buffer;
    const int status = ::pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

#ifdef RSL_RSL_EXECUTABLE
// The `rsl` program with arguments (the binary this build made).
inline std::pair<int, std::string> run_rsl(const std::string& arguments) {
    return run_command(std::string(RSL_RSL_EXECUTABLE) + " " + arguments);
}
#endif

// Collects every rsl::warn() message while alive (instead of printing it).
class WarningCapture {
public:
    WarningCapture()
        : previous_(set_warning_handler([this](const std::string& message) { messages_.push_back(message); })) {}
    ~WarningCapture() { set_warning_handler(std::move(previous_)); }
    WarningCapture(const WarningCapture&) = delete;
    WarningCapture& operator=(const WarningCapture&) = delete;

    const std::vector<std::string>& messages() const { return messages_; }

private:
    std::vector<std::string> messages_;
    WarningHandler previous_;
};

}  // namespace rsl::test
