// `rsl demo NAME`: the demos of docs/DEMOS.md, rendered headless with the CPU
// runtime renderer into an image sequence, a contact sheet and (with ffmpeg)
// an MP4. `rsl view demos/NAME/scene.json` shows the same scenes live.
#include <fmt/core.h>

#include "demos/demo.h"
#include "tools/rsl/command.h"
#include "tools/rsl/data_folder.h"
#include "src/core/error.h"

namespace rsl::cli {
namespace {

struct DemoArgs {
    std::string name;
    std::string out;
    std::string cache;
    int frames = 0, width = 0, height = 0;
    bool quick = false, quiet = false;
};

void run_demo_command(const DemoArgs& args) {
    if (args.name == "list") {
        for (const demos::DemoInfo& demo : demos::demo_list())
            fmt::print("{:<10} {}  (demos/{})\n", demo.name, demo.description, demo.scene);
        return;
    }
    if (args.frames < 0 || args.width < 0 || args.height < 0)
        throw_error("--frames, --width and --height must be positive");
    demos::DemoOptions options;
    options.out_dir = args.out.empty() ? std::filesystem::path("out") / "demos" / args.name : std::filesystem::path(args.out);
    options.demos_dir = data_folder() / "demos";
    // The fields go beside the frames, not beside the demo's scene file (the
    // source tree, or an installed package's read-only share/rsl).
    options.field_cache = args.cache.empty() ? options.out_dir / ".rsl-cache" : std::filesystem::path(args.cache);
    options.frames = args.frames;
    options.width = args.width;
    options.height = args.height;
    options.quick = args.quick;
    options.progress = !args.quiet;
    const demos::DemoResult result = demos::run_demo(args.name, options);
    fmt::print("{}: {} frame(s), contact sheet {}{}\n", result.name, result.frames.size(),
               result.contact_sheet.string(), result.mp4.empty() ? "" : ", video " + result.mp4.string());
    fmt::print("  setup (load, fit, bake) {:.2f} s\n", result.setup_seconds);
    for (const std::string& line : demos::timing_summary(result)) fmt::print("  {}\n", line);
    for (const std::string& line : result.notes) fmt::print("  {}\n", line);
}

RegisterCommand demo_command({"demo",
    "Run a demo headless (robot, kitchen, materials, compare): frames, contact sheet, MP4 with ffmpeg.", 60,
    [](CLI::App& app) {
        auto args = std::make_shared<DemoArgs>();
        app.add_option("name", args->name, "robot, kitchen, materials, compare; `list` lists them")->required();
        app.add_option("--out,-o", args->out, "Output folder (default out/demos/NAME, under the current folder)");
        app.add_option("--cache", args->cache,
                       "Field cache folder (default: OUT/.rsl-cache); a second run with the same cache bakes nothing");
        app.add_option("--frames", args->frames, "Number of frames (default: the demo's)");
        app.add_option("--width", args->width, "Frame width in pixels");
        app.add_option("--height", args->height, "Frame height in pixels");
        app.add_flag("--quick", args->quick, "Small precompute and 8 lights (tests, first look)");
        app.add_flag("--quiet,-q", args->quiet, "No progress lines");
        app.callback([args] { run_demo_command(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
