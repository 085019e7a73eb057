#pragma once
// The demos (docs/DEMOS.md): each renders a scene file of demos/ headless with
// the CPU runtime renderer into an image sequence, a contact sheet PNG and,
// when ffmpeg is installed, an MP4. The same scene files open in `rsl view`.
//
//   robot      12-part walking robot, rotating sun/sky, camera path (paper Fig. 13)
//   kitchen    5 parts, two environment maps cross-faded, a moving local light (Fig. 16)
//   materials  one object, four BRDFs, a glossiness sweep that rebuilds the tables every frame (Fig. 15)
//   compare    ground truth vs RSL with 10, 30 and 100 lights, error images (Figs. 9, 10)
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rsl::demos {

struct DemoOptions {
    std::filesystem::path out_dir;        // empty: out/demos/<name>
    std::filesystem::path demos_dir;      // where the scene files live; empty: the source tree's demos/
    std::filesystem::path field_cache;    // field cache folder; empty: beside each demo's scene file
    int frames = 0;                       // 0: the demo's default
    int width = 0, height = 0;            // 0: the demo's default
    // Small precompute and few lights: for tests and a first look (docs/DEMOS.md).
    bool quick = false;
    bool progress = true;                 // bake progress and one line per frame on stdout/stderr
};

struct FrameTiming {
    float time = 0;             // scene time (s)
    double shade_seconds = 0;   // vertex colours (all renderers of the frame)
    double image_seconds = 0;   // primary rays + interpolation
    double update_seconds = 0;  // per-frame scene edits (materials: the BRDF table rebuild)
};

struct DemoResult {
    std::string name;
    std::vector<std::filesystem::path> frames;  // PNG image sequence
    std::filesystem::path contact_sheet;        // PNG
    std::filesystem::path mp4;                  // empty when ffmpeg is not installed
    std::vector<FrameTiming> timings;
    double setup_seconds = 0;                   // scene load, light fitting, field baking
    std::vector<std::string> notes;             // measurements worth printing (errors, rebuild times)
    // Named numbers for tests and reports, e.g. compare: "pixel_error_K10" (relative L2).
    std::map<std::string, double> metrics;
};

struct DemoInfo {
    std::string name;
    std::string description;
    std::string scene;  // scene file relative to the demos folder
};
const std::vector<DemoInfo>& demo_list();

// Runs one demo; throws rsl::Error for an unknown name or any failure.
DemoResult run_demo(const std::string& name, const DemoOptions& options);

// One line per frame-time statistic (mean/min/max per phase), for the report.
std::vector<std::string> timing_summary(const DemoResult& result);

}  // namespace rsl::demos
