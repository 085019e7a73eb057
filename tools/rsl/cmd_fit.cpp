// `rsl fit ENV --lights K -o lights.json [--preview fit.png]`: decompose an
// environment map into rotatable square lights (docs/design/LIGHTFIT.md).
#include <chrono>

#include <fmt/core.h>

#include "src/formats/environment_file.h"
#include "src/formats/image_file.h"
#include "src/lightfit/decompose.h"
#include "src/lightfit/reconstruct.h"
#include "tools/rsl/command.h"
#include "src/core/atomic_file.h"
#include "src/core/envmap.h"
#include "src/core/error.h"

namespace rsl::cli {
namespace {

struct FitArgs {
    std::string environment;
    std::string output;
    std::string preview;
    int lights = 30;
    int resolution = 32;
    bool cross_face = false, same_face = false;
    std::string merge_cost = "increase";
    double max_error = 0;
    int preview_width = 512;
};

void run_fit(const FitArgs& args) {
    if (args.resolution < 1 || args.resolution > kMaxCubeResolution)
        throw_error("--resolution {}: expected 1..{} texels per cube-face edge", args.resolution, kMaxCubeResolution);
    if (args.lights < 1) throw_error("--lights {}: expected at least 1", args.lights);
    if (args.max_error < 0) throw_error("--max-error {}: expected ≥ 0", args.max_error);

    lightfit::DecomposeOptions options;
    options.lights = args.lights;
    options.max_error = args.max_error;
    if (args.same_face) options.cross_face = false;
    if (args.cross_face) options.cross_face = true;
    options.cost = args.merge_cost == "increase" ? lightfit::MergeCost::kErrorIncrease : lightfit::MergeCost::kMergedError;
    if (!options.cross_face && options.lights < 6)
        throw_error("--lights {} with --same-face: regions never cross a cube face, so at least 6", options.lights);

    if (!args.preview.empty() && std::filesystem::path(args.preview).extension() != ".png")
        throw_error("--preview {}: expected a .png path (the preview is a PNG image)", args.preview);
    check_outputs_apart({args.output, args.preview}, {args.environment});
    const CubeMap map = load_environment(args.environment, args.resolution);
    const auto start = std::chrono::steady_clock::now();
    const RslSet set = lightfit::decompose(map, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    save_rsl_set(args.output, set);

    const DVec3 energy = map.energy(), lights = set.total_energy();
    const double error = lightfit::relative_l2_error(map, lightfit::reconstruct(set, map.resolution()));
    fmt::print("{}: 6x{}x{} texels -> {} RSLs ({}, {} merge cost) in {:.3f} s\n", args.environment, map.resolution(),
               map.resolution(), set.lights.size(), options.cross_face ? "cross-face" : "same-face", args.merge_cost,
               seconds);
    fmt::print("  energy  map ({:.6g}, {:.6g}, {:.6g})  lights ({:.6g}, {:.6g}, {:.6g})\n", energy.r, energy.g,
               energy.b, lights.r, lights.g, lights.b);
    fmt::print("  relative L2 error of the reconstructed map: {:.4f}\n", error);
    fmt::print("  wrote {}\n", args.output);
    if (!args.preview.empty()) {
        write_png(args.preview, lightfit::fit_preview(map, set, args.preview_width));
        fmt::print("  wrote {}\n", args.preview);
    }
}

RegisterCommand fit_command({"fit",
    "Decompose an environment map (.exr/.hdr, lat-long or cube strip) into rotatable square lights.", 10,
    [](CLI::App& app) {
        auto args = std::make_shared<FitArgs>();
        app.add_option("environment", args->environment, "Environment map")->required()->check(CLI::ExistingFile);
        app.add_option("-o,--output", args->output, "RSL set to write (JSON)")->required();
        app.add_option("--lights,-k", args->lights, "Number of RSLs (a lower bound with --max-error)")
            ->capture_default_str();
        app.add_option("--resolution,-n", args->resolution, "Cube-map face resolution N (6xNxN texels)")
            ->capture_default_str();
        auto* cross = app.add_flag("--cross-face", args->cross_face, "Let regions cross cube-face borders (default)");
        auto* same = app.add_flag("--same-face", args->same_face, "Keep every region within one cube face (the paper)");
        cross->excludes(same);
        app.add_option("--merge-cost", args->merge_cost,
                       "merged: merge the pair whose merged fit error is least (the paper); "
                       "increase: the pair that raises the summed error least")
            ->check(CLI::IsMember({"merged", "increase"}))
            ->capture_default_str();
        app.add_option("--max-error", args->max_error,
                       "Stop before a merge whose fit error (relative to |map energy|^2) exceeds this; 0: off")
            ->capture_default_str();
        app.add_option("--preview", args->preview, "FILE.png: map | regions | reconstruction, like the paper's Figure 6");
        app.add_option("--preview-width", args->preview_width, "Width of each preview panel")->capture_default_str();
        app.callback([args] { run_fit(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
