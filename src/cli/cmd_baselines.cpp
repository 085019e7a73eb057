// `rsl baselines SCENE --time T -o DIR`: one static frame of a scene rendered
// with every method against the ground truth (docs/BASELINES.md). The
// experiment itself is bench/baselines_experiment; this file only parses the
// command line.
#include <string>
#include <vector>

#include "baselines/sh.h"
#include "bench/baselines_experiment.h"
#include "src/cli/command.h"
#include "src/core/error.h"

namespace rsl::cli {
namespace {

std::vector<int> parse_list(const std::string& text, const char* what) {
    std::vector<int> values;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        try {
            values.push_back(std::stoi(text.substr(start, comma - start)));
        } catch (const std::exception&) {
            throw_error("{} '{}': expected comma-separated integers", what, text);
        }
        if (values.back() < 1) throw_error("{} '{}': every value must be at least 1", what, text);
        start = comma + 1;
    }
    return values;
}

RegisterCommand baselines_command({"baselines",
    "Render one static frame with SH PRT, Haar PRT, RSL and the ground truth; write the error table and figures.",
    60, [](CLI::App& app) {
        auto args = std::make_shared<BaselinesExperiment>();
        auto sh = std::make_shared<std::string>("3,5,10");
        auto haar = std::make_shared<std::string>("20,30,60,100");
        auto rsl = std::make_shared<std::string>("10,30,60,100");
        app.add_option("scene", args->scene, "Scene file (.json, .gltf/.glb, .obj)")->required()->check(CLI::ExistingFile);
        app.add_option("--time,-t", args->time, "Time in seconds (the static frame)")->capture_default_str();
        app.add_option("-o,--output", args->output, "Output folder")->capture_default_str();
        app.add_option("--environment", args->environment, "Use this probe instead of the scene's")
            ->check(CLI::ExistingFile);
        app.add_flag("--diffuse", args->diffuse, "Make every material Lambertian (its diffuse colour kept)");
        app.add_option("--resolution", args->resolution, "Cube map N (a power of two; default: the scene's)");
        app.add_option("--sh-orders", *sh, "SH orders n (n^2 coefficients)")->capture_default_str();
        app.add_option("--haar-terms", *haar, "Haar lighting terms N")->capture_default_str();
        app.add_option("--rsl-lights", *rsl, "RSL counts K")->capture_default_str();
        app.add_flag("--no-rsl", args->no_rsl, "Skip the RSL renderer (no field bake)");
        app.add_option("--haar-drop", args->haar_drop, "Drop transport wavelets below this x the vertex's largest")
            ->capture_default_str();
        app.add_option("--width", args->width, "Image width")->capture_default_str();
        app.add_option("--height", args->height, "Image height")->capture_default_str();
        app.add_option("--repeats", args->repeats, "Frames timed per method (median)")->capture_default_str();
        app.add_flag("--quiet,-q", args->quiet, "No progress lines");
        app.callback([args, sh, haar, rsl] {
            args->sh_orders = parse_list(*sh, "--sh-orders");
            for (int order : args->sh_orders)
                if (order > sh::kMaxOrder) throw_error("--sh-orders: order {} is above {}", order, sh::kMaxOrder);
            args->haar_terms = parse_list(*haar, "--haar-terms");
            args->rsl_lights = parse_list(*rsl, "--rsl-lights");
            run_baselines_experiment(*args);
        });
    }});

}  // namespace
}  // namespace rsl::cli
