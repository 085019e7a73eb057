// Every demo, headless, short and small (--quick: tiny precompute, 8 lights):
// the outputs exist and decode, frames are not blank, and they change over
// time. Plus the pieces the demos script: the environment cross-fade weight,
// the glossiness sweep, the vertex-colour blend.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>

#include <unistd.h>

// stb_image's implementation is in rsl_formats (src/formats/gltf_materials.cpp).

#include "demos/demo.h"
#include "demos/demo_runners.h"
#include "demos/demo_support.h"
#include "src/brdf/brdf.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "tests/png_test_support.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::demos;
namespace fs = std::filesystem;

namespace {

// Per-process scratch folder (several builds may run the suite at once),
// removed when the test program exits.
fs::path scratch_dir() {
    static const struct Scratch {
        fs::path dir = fs::temp_directory_path() / fmt::format("rsl_demos_test_{}", ::getpid());
        Scratch() { fs::create_directories(dir); }
        ~Scratch() { std::error_code ignored; fs::remove_all(dir, ignored); }
    } scratch;
    return scratch.dir;
}

using test::Png;
using test::read_png;

// Standard deviation of the 8-bit luma over the image: 0 for a flat image.
double luma_deviation(const Png& png) {
    double sum = 0, sum2 = 0;
    const size_t n = size_t(png.width) * png.height;
    for (size_t p = 0; p < n; ++p) {
        const double y = 0.2126 * png.rgb[3 * p] + 0.7152 * png.rgb[3 * p + 1] + 0.0722 * png.rgb[3 * p + 2];
        sum += y, sum2 += y * y;
    }
    const double mean = sum / double(n);
    return std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean));
}

// Fraction of pixels whose colour differs by more than 2 levels in some channel.
double changed_fraction(const Png& a, const Png& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    size_t changed = 0;
    const size_t n = size_t(a.width) * a.height;
    for (size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(a.rgb[3 * p + c]) - int(b.rgb[3 * p + c])) > 2) {
                ++changed;
                break;
            }
    return double(changed) / double(n);
}

constexpr int kWidth = 48, kHeight = 36, kFrames = 3;

DemoResult run_quick(const std::string& name) {
    DemoOptions options;
    options.out_dir = scratch_dir() / name;
    options.field_cache = scratch_dir() / ".rsl-cache";  // nothing written into the source tree
    options.frames = kFrames;
    options.width = kWidth;
    options.height = kHeight;
    options.quick = true;
    options.progress = false;
    return run_demo(name, options);
}

// The checks every animated demo passes.
void check_animated(const DemoResult& result) {
    REQUIRE(result.frames.size() == size_t(kFrames));
    REQUIRE(result.timings.size() == size_t(kFrames));
    std::vector<Png> frames;
    for (const fs::path& path : result.frames) {
        frames.push_back(read_png(path));
        REQUIRE(frames.back().width == kWidth);
        REQUIRE(frames.back().height == kHeight);
        INFO(path.string());
        REQUIRE(luma_deviation(frames.back()) > 8.0);  // not blank: the scene shows structure
    }
    for (size_t f = 1; f < frames.size(); ++f) {
        INFO("frame " << f << " vs frame " << f - 1);
        REQUIRE(changed_fraction(frames[f], frames[f - 1]) > 0.02);  // it moves
    }
    const Png sheet = read_png(result.contact_sheet);
    REQUIRE(sheet.width > kFrames * kWidth);  // every frame (and gaps) side by side
    REQUIRE(sheet.height > kHeight);
    REQUIRE(luma_deviation(sheet) > 8.0);
    for (const FrameTiming& timing : result.timings) REQUIRE(timing.shade_seconds > 0);
}

}  // namespace

TEST_CASE("robot demo renders a moving, non-blank sequence", "[demos][robot]") {
    check_animated(run_quick("robot"));
}

TEST_CASE("walker demo renders a moving, non-blank sequence", "[demos][walker]") {
    check_animated(run_quick("walker"));
}

TEST_CASE("kitchen demo renders a moving, non-blank sequence", "[demos][kitchen]") {
    check_animated(run_quick("kitchen"));
}

TEST_CASE("materials demo changes the frames only through the glossiness edit", "[demos][materials]") {
    const DemoResult result = run_quick("materials");
    check_animated(result);  // the scene does not move: the change is the table rebuild
    REQUIRE(result.metrics.at("table_rebuild_seconds") > 0);
}

TEST_CASE("compare demo: truth, 10/30/100 lights and error images, RSL close to the truth", "[demos][compare]") {
    const DemoResult result = run_quick("compare");
    REQUIRE(result.frames.size() == 7);  // truth + 3 × (RSL, error)
    for (const fs::path& path : result.frames) {
        const Png png = read_png(path);
        REQUIRE(png.width == kWidth);
        REQUIRE(png.height == kHeight);
        INFO(path.string());
        REQUIRE(luma_deviation(png) > 2.0);  // error images too: the RSL result is not exact
    }
    REQUIRE(luma_deviation(read_png(result.frames.front())) > 8.0);
    const Png sheet = read_png(result.contact_sheet);
    REQUIRE(sheet.width > 4 * kWidth);
    REQUIRE(sheet.height > 2 * kHeight);
    // With --quick (8x8 visibility tables, 6x8x8 cube map) the error is dominated
    // by the coarse fields, not by the light count (docs/DEMOS.md), so the test
    // pins closeness, not the ordering over K.
    for (int lights : {10, 30, 100}) {
        const double pixels = result.metrics.at(fmt::format("pixel_error_K{}", lights));
        const double vertices = result.metrics.at(fmt::format("vertex_error_K{}", lights));
        INFO(lights << " lights: relative L2 error " << pixels << " (pixels), " << vertices << " (vertices)");
        REQUIRE(pixels > 0.0);
        REQUIRE(pixels < 0.5);
        REQUIRE(vertices > 0.0);
        REQUIRE(vertices < 0.5);
    }
}

TEST_CASE("unknown demo names are refused with the list", "[demos]") {
    try {
        run_demo("teapot", DemoOptions{});
        FAIL("no error");
    } catch (const Error& e) {
        REQUIRE(std::string(e.what()).find("robot") != std::string::npos);
    }
}

TEST_CASE("weighted vertex-colour sum is the per-vertex linear combination", "[demos]") {
    VertexColors a, b, out;
    for (VertexColors* c : {&a, &b, &out}) c->add_part("p", 3), c->add_part("q", 1);
    a.parts[0] = {Color(1, 2, 3), Color(0), Color(4)};
    a.parts[1] = {Color(1)};
    b.parts[0] = {Color(3, 2, 1), Color(1), Color(0)};
    b.parts[1] = {Color(5)};
    weighted_sum(out, {&a, &b}, {0.25f, 0.75f});
    REQUIRE(out.parts[0][0] == Color(2.5f, 2.0f, 1.5f));
    REQUIRE(out.parts[0][1] == Color(0.75f));
    REQUIRE(out.parts[0][2] == Color(1.0f));
    REQUIRE(out.parts[1][0] == Color(4.0f));
}

TEST_CASE("glossiness sweep sets valid parameters for every swept model, rougher as it goes", "[demos]") {
    const std::vector<MaterialDesc> models{
        {"steel", "phong", {{"kd", {0.1f, 0.1f, 0.1f}}, {"ks", {0.7f, 0.7f, 0.7f}}, {"exponent", {100}}}, {}, nullptr},
        {"bronze", "cook_torrance_beckmann", {{"f0", {0.8f, 0.5f, 0.25f}}, {"roughness", {0.2f}}}, {}, nullptr},
        {"metal", "ward", {{"kd", {0.1f, 0.1f, 0.1f}}, {"ks", {0.6f, 0.6f, 0.6f}}, {"alpha", {0.15f}}}, {}, nullptr},
        {"brushed", "ward_anisotropic",
         {{"kd", {0.1f, 0.1f, 0.1f}}, {"ks", {0.6f, 0.6f, 0.6f}}, {"alpha_x", {0.3f}}, {"alpha_y", {0.08f}}}, {}, nullptr},
    };
    const int frames = 5;
    for (const MaterialDesc& model : models) {
        INFO(model.model);
        float previous_peak = 1e30f;
        for (int f = 0; f < frames; ++f) {
            MaterialDesc edited = model;
            set_glossiness(edited, sweep_roughness(f, frames));
            const auto brdf = make_brdf(edited);  // validates every parameter
            // Mirror configuration at 45°: the lobe's peak falls as roughness grows.
            const Vec3 wi = glm::normalize(Vec3(0.7f, 0.0f, 0.7f)), wo = glm::normalize(Vec3(-0.7f, 0.0f, 0.7f));
            const float peak = luminance(brdf->eval(wi, wo));
            REQUIRE(peak < previous_peak);
            previous_peak = peak;
        }
    }
    MaterialDesc lambert{"floor", "lambert", {{"albedo", {0.5f, 0.5f, 0.5f}}}, {}, nullptr};
    REQUIRE_THROWS_AS(set_glossiness(lambert, 0.2f), Error);
    REQUIRE(sweep_roughness(0, 12) < sweep_roughness(11, 12));
}

TEST_CASE("frame sequences: numbered PNGs, a contact sheet, and an MP4 exactly when ffmpeg is on PATH", "[demos]") {
    // A stand-in ffmpeg that writes its arguments into its output file (the
    // last argument), so the test sees the command without the real encoder.
    const fs::path bin = scratch_dir() / "fake-bin";
    fs::create_directories(bin);
    {
        std::ofstream script(bin / "ffmpeg");
        script << "#!/bin/sh\nfor a; do last=\"$a\"; done\necho \"$@\" > \"$last\"\n";
    }
    fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
    const std::string saved_path = std::getenv("PATH") ? std::getenv("PATH") : "";

    Image frame(20, 10, 3);
    for (size_t i = 0; i < frame.pixels.size(); ++i) frame.pixels[i] = float(i % 7) / 7.0f;
    for (const bool with_ffmpeg : {false, true}) {
        INFO("ffmpeg on PATH: " << with_ffmpeg);
        ::setenv("PATH", with_ffmpeg ? (bin.string() + ":" + saved_path).c_str() : "/nonexistent", 1);
        const fs::path folder = scratch_dir() / (with_ffmpeg ? "seq-ffmpeg" : "seq-plain");
        DemoResult result;
        result.name = "seq";
        FrameSequence sequence(folder);
        for (int f = 0; f < 3; ++f) REQUIRE(sequence.add(frame, "f") == folder / fmt::format("frame_{:04d}.png", f));
        sequence.finish(result, 12.0f);
        ::setenv("PATH", saved_path.c_str(), 1);
        REQUIRE(result.frames.size() == 3);
        REQUIRE(read_png(result.contact_sheet).width > 3 * 20);
        if (!with_ffmpeg) {
            REQUIRE(result.mp4.empty());
            continue;
        }
        REQUIRE(result.mp4 == folder / "seq.mp4");
        const std::string args = read_file(result.mp4);  // the fake encoder's record of its command line
        REQUIRE(args.find("-framerate 12") != std::string::npos);
        REQUIRE(args.find((folder / "frame_%04d.png").string()) != std::string::npos);
        REQUIRE(args.find("yuv420p") != std::string::npos);
        for (const auto& entry : fs::directory_iterator(folder))  // written atomically: no temporary left
            REQUIRE(entry.path().filename().string().find(".rsl-tmp-") == std::string::npos);
    }
}

TEST_CASE("rsl demo writes its frames and field cache into --out, nothing beside the demo's scene",
          "[demos][cli]") {
    // The source tree's cache of the demo, as it stands (absent, or left by an earlier run of another kind).
    const fs::path source_cache = fs::path(RSL_SOURCE_DIR) / "demos" / "materials" / ".rsl-cache";
    const auto listing = [](const fs::path& folder) {
        std::map<std::string, fs::file_time_type> files;
        std::error_code error;
        for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
            files[it->path().filename().string()] = it->last_write_time();
        return files;
    };
    const auto before = listing(source_cache);
    const fs::path out = scratch_dir() / "cli_demo";
    const auto [status, text] = test::run_rsl("demo materials --quick --frames 1 --width 24 --height 18 -q --out " +
                                              out.string());
    INFO(text);
    REQUIRE(status == 0);
    CHECK(fs::exists(out / "frame_0000.png"));
    size_t fields = 0;
    for (const auto& [name, time] : listing(out / ".rsl-cache")) fields += name.size() > 5 && name.substr(name.size() - 5) == ".rslf";
    CHECK(fields > 0);
    CHECK(listing(source_cache) == before);
}
