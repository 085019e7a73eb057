#pragma once
// What every libFuzzer harness of fuzz/ shares (docs/design/FUZZING.md). A harness
// hands the input to the real reader through a file (the readers take
// paths) and runs it under run_reader: an rsl::Error is the reader refusing
// bad input, which is what it should do; any other exception, a crash, a
// sanitizer report, or a result that breaks what the reader promises (the
// check_* functions below) is a finding, reported by aborting so that
// libFuzzer saves the input.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <typeinfo>

#include <fmt/core.h>

#include "src/core/error.h"
#include "src/core/mesh.h"
#include "src/core/scene.h"

namespace rsl::fuzz {

// Writes the input to this process's scratch folder as input<extension>
// (a folder removed at exit) and returns its path.
std::filesystem::path write_input(const uint8_t* data, size_t size, const std::string& extension);
std::filesystem::path write_input(const std::string& bytes, const std::string& extension);
// This process's scratch folder.
const std::filesystem::path& scratch_dir();

// Prints "rsl fuzz finding: ..." and aborts.
[[noreturn]] void report_finding(const std::string& message);
template <typename... Args>
[[noreturn]] void finding(fmt::format_string<Args...> format, Args&&... args) {
    report_finding(fmt::format(format, std::forward<Args>(args)...));
}
#define RSL_FUZZ_EXPECT(cond)                                                        \
    do {                                                                             \
        if (!(cond)) ::rsl::fuzz::finding("{}:{}: {}", __FILE__, __LINE__, #cond); \
    } while (0)

// Silences rsl::warn (the readers' warnings are expected on mutated input).
void silence_warnings();

// Runs read(); a refusal (rsl::Error) is fine, anything else is a finding.
template <typename Read>
int run_reader(Read&& read) {
    silence_warnings();
    try {
        read();
    } catch (const Error&) {
        // Refused, naming the file: the reader did its job.
    } catch (const std::exception& e) {
        finding("{} escaped the reader (not an rsl::Error): {}", typeid(e).name(), e.what());
    } catch (...) {
        finding("a non-std exception escaped the reader");
    }
    return 0;
}

// What an accepted mesh promises (src/core/mesh.h, validate_and_complete):
// triangles indexing existing vertices, finite positions, unit normals, unit
// tangents orthogonal to them with handedness ±1.
void check_mesh(const TriangleMesh& mesh);
// What an accepted scene promises: valid part, node and material indices, an
// acyclic node tree, keyed tracks whose sizes match, meshes as above; and
// that posing it (node_world_at at the animation's ends) does not crash.
void check_scene(const Scene& scene);

}  // namespace rsl::fuzz
