// Every input the project keeps for its readers — the fuzzers' seed corpora
// (fuzz/corpus), the inputs fuzzing found (fuzz/regressions) and the hostile
// files the regression tests build (tests/hostile_inputs.h) — run through
// the `rsl` program as a user would: `rsl info` on each, `rsl fit` on each
// environment map. None may end in an internal error (status 2) or a crash;
// the seeds, valid by construction, must be read (status 0), the hostile
// files refused (status 1).
#include <catch2/catch.hpp>

#include "fuzz/fixup.h"
#include "fuzz/seeds/seeds.h"
#include "src/core/atomic_file.h"
#include "tests/hostile_inputs.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

const fs::path kFuzzDir = fs::path(RSL_SOURCE_DIR) / "fuzz";

struct Input {
    fs::path file;
    int expected = -1;  // the status `rsl info` must give; -1: 0 or 1
};

// `file` copied into `dir` (scene files beside the files they name), with
// the fix-up the fuzzer applied to .rslf/.rslv inputs before reading them.
fs::path staged(const fs::path& file, const fs::path& dir) {
    std::string bytes = read_bytes(file);
    if (file.extension() == ".rslf") fuzz::fix_field_file(bytes);
    if (file.extension() == ".rslv") fuzz::fix_trailing_checksum(bytes);
    const fs::path copy = dir / (file.parent_path().filename().string() + "_" + file.filename().string());
    write_file_atomically(copy, bytes);
    return copy;
}

std::vector<Input> kept_inputs(const fs::path& dir) {
    std::vector<Input> inputs;
    for (const char* folder : {"corpus", "regressions"}) {
        if (!fs::exists(kFuzzDir / folder)) continue;
        for (const auto& entry : fs::recursive_directory_iterator(kFuzzDir / folder))
            if (entry.is_regular_file())
                inputs.push_back({staged(entry.path(), dir), std::string(folder) == "corpus" ? 0 : -1});
    }
    return inputs;
}

std::vector<Input> hostile_inputs(const fs::path& dir) {
    using namespace hostile;
    const std::vector<std::pair<std::string, std::string>> files = {
        {"flipped.hdr", flipped_exponent_hdr()},
        {"oversized.hdr", oversized_hdr()},
        {"wide_latlong.exr", wide_latlong_exr(dir)},
        {"wide_plain.exr", wide_plain_exr(dir)},
        {"huge_attribute.exr", exr_huge_attribute(dir)},
        {"misaligned.exr", exr_misaligned_attribute(dir)},
        {"overflow.json", overflow_scene()},
        {"overflow_array.json", overflow_array_scene()},
        {"nan_table.rslf", svdf_with_nan(dir, 3)},
        {"nan_center.rslf", ovdf_nan_center(dir)},
        {"count_overflow.gltf", gltf_count_overflow()},
        {"directory_buffer.gltf", gltf_directory_buffer()},
    };
    std::vector<Input> inputs;
    for (const auto& [name, bytes] : files) {
        write_file_atomically(dir / name, bytes);
        inputs.push_back({dir / name, 1});
    }
    write_file_atomically(dir / "huge_normals.obj", huge_normals_obj());  // now read: the normals are directions
    inputs.push_back({dir / "huge_normals.obj", 0});
    return inputs;
}

// The edge seeds (fuzz/corpus/scene/edges.json, gltf and glb depth_limit) one
// step past their limits: each must be refused (status 1), naming the problem.
struct PastLimit {
    std::string name, contents, problem;
};

std::vector<PastLimit> past_limits() {
    const std::string edges = read_bytes(kFuzzDir / "corpus" / "scene" / "edges.json");
    const auto edited = [&](const std::string& from, const std::string& to) {
        std::string text = edges;
        const size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        return text.replace(at, from.size(), to);
    };
    std::string gltf = read_bytes(kFuzzDir / "corpus" / "gltf" / "depth_limit.gltf");
    gltf.insert(gltf.find(R"(,"generator")"), "]");
    gltf.insert(gltf.find(R"("extras":)") + 9, "[");
    return {
        {"power.json", edited("[1e12, 1e12, 1e12]", "[1.0001e12, 1e12, 1e12]"), "past the limit"},
        {"radiance.json", edited("0.0504", "0.0502"), "past the limit"},
        {"power_nan.json", edited("[1e12, 1e12, 1e12]", R"(["nan", 1, 1])"), "lights[0].power"},
        {"power_inf.json", edited("[1e12, 1e12, 1e12]", "[1e309, 1, 1]"), "lights[0].power"},
        {"roughness_inf.json", edited(R"("roughness": 1e-3)", R"("roughness": "inf")"), "roughness"},
        {"resolution.json", edited(R"("resolution": 512)", R"("resolution": 513)"), "resolution"},
        {"width.json", edited(R"("width": 16384)", R"("width": 16385)"), "width"},
        {"huge_scale.json", edited("[1e19, 1e19, 3]", "[1e19, 1e19, 4]"), "part 'ball': its transform"},
        {"tiny_scale.json", edited("[1e-10, 1e-10, 2]", "[1e-10, 1e-10, 0.5]"), "part 'plain': its transform"},
        {"deep.gltf", gltf, "JSON nested deeper than 256 levels"},
    };
}

}  // namespace

TEST_CASE("The fuzzers' edge seeds are read, and one step past each limit is refused", "[fuzz][bad-input][cli]") {
    const fs::path dir = scratch_dir("input_sweep_edges");
    fuzz::write_scene_support_files(dir);
    for (const char* seed : {"scene/edges.json", "gltf/depth_limit.gltf", "glb/depth_limit.glb"}) {
        const auto [status, text] = run_rsl("info " + staged(kFuzzDir / "corpus" / seed, dir).string());
        INFO(seed << ": " << text);
        CHECK(status == 0);
    }
    for (const PastLimit& input : past_limits()) {
        write_file_atomically(dir / input.name, input.contents);
        const auto [status, text] = run_rsl("info " + (dir / input.name).string());
        INFO(input.name << ": " << text);
        CHECK(status == 1);
        CHECK(text.find(input.name) != std::string::npos);
        CHECK(text.find(input.problem) != std::string::npos);
    }
    fs::remove_all(dir);
}

TEST_CASE("No kept or hostile input makes rsl end in an internal error or a crash", "[fuzz][bad-input][cli]") {
    const fs::path dir = scratch_dir("input_sweep");
    fuzz::write_scene_support_files(dir);  // what the scene seeds name
    std::vector<Input> inputs = kept_inputs(dir);
    const size_t kept = inputs.size();
    for (const Input& input : hostile_inputs(dir)) inputs.push_back(input);
    CHECK(kept >= 30);  // every reader's seeds
    int refused = 0, maps = 0;
    for (const Input& input : inputs) {
        const auto [status, text] = run_rsl("info " + input.file.string());
        INFO(input.file.filename().string() << ": status " << status << "\n" << text);
        CHECK((status == 0 || status == 1));  // not 2 (internal error), not -1 (killed by a signal)
        if (input.expected >= 0) CHECK(status == input.expected);
        CHECK(text.find("internal error") == std::string::npos);
        refused += status == 1;
        // What `rsl info` accepts as an environment map, `rsl fit` fits.
        const std::string ext = input.file.extension().string();
        if ((ext == ".hdr" || ext == ".exr") && status == 0 && text.find(": environment map\n") != std::string::npos) {
            const fs::path lights = dir / "lights.json";
            const auto [fit, fit_text] = run_rsl(fmt::format("fit {} -o {} --lights 4 -n 8", input.file.string(),
                                                             lights.string()));
            INFO(fit_text);
            CHECK(fit == 0);
            CHECK(run_rsl("info " + lights.string()).first == 0);
            ++maps;
        }
    }
    CHECK(refused >= 12);
    CHECK(maps >= 8);
    fs::remove_all(dir);
}
