// `rsl baselines SCENE --time T -o DIR`: one static frame of a scene rendered
// with every method against the ground truth (docs/BASELINES.md); with
// --many-light, the ray-traced and shadow-mapped many-light baselines
// instead of the PRT ones. The experiments themselves are
// tools/bench/baselines_experiment and tools/bench/many_light_experiment; this file only
// parses the command line.
#include <string>
#include <vector>

#include "tools/baselines/sh.h"
#include "tools/bench/baselines_experiment.h"
#include "tools/bench/many_light_experiment.h"
#include "tools/rsl/command.h"
#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/render/render_options.h"

namespace rsl::cli {
namespace {

std::vector<int> parse_list(const std::string& text, const char* what, bool allow_empty = false) {
    std::vector<int> values;
    if (text.empty() && allow_empty) return values;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        size_t used = 0;
        try {
            values.push_back(std::stoi(item, &used));
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size())  // "2x" is not 2
            throw_error("{} '{}': expected comma-separated integers", what, text);
        if (values.back() < 1) throw_error("{} '{}': every value must be at least 1", what, text);
        start = comma + 1;
    }
    return values;
}

RegisterCommand baselines_command({"baselines",
    "Render one static frame with SH PRT, Haar PRT, eigentransport, the wavelet triple product, RSL and the ground "
    "truth (or, with --many-light, RSL against "
    "ray-traced and shadow-mapped many-light shadows); write the error table and figures.",
    60, [](CLI::App& app) {
        auto args = std::make_shared<BaselinesExperiment>();
        auto many = std::make_shared<ManyLightExperiment>();
        auto many_light = std::make_shared<bool>(false);
        auto sh = std::make_shared<std::string>("3,5,10");
        auto haar = std::make_shared<std::string>("20,30,60,100");
        auto eigen = std::make_shared<std::string>("16,48,128");
        auto rsl = std::make_shared<std::string>("10,30,60,100");
        auto triple = std::make_shared<std::string>("80,320");
        auto lookup = std::make_shared<std::string>("bilinear");
        auto rays = std::make_shared<std::string>("1,2,4");
        auto maps = std::make_shared<std::string>("256,1024");
        auto gl_lights = std::make_shared<std::string>("30");
        auto gl_rays = std::make_shared<std::string>("1,2");
        auto env_rays = std::make_shared<std::string>("1,4,16,64,256");
        app.add_option("scene", args->scene, "Scene file (.json, .gltf/.glb, .obj)")->required()->check(CLI::ExistingFile);
        app.add_option("--time,-t", args->time, "Time in seconds (the static frame)")->capture_default_str();
        app.add_option("-o,--output", args->output, "Output folder (default out/baselines, or out/many_light)");
        app.add_option("--environment", args->environment, "Use this probe instead of the scene's")
            ->check(CLI::ExistingFile);
        app.add_flag("--diffuse", args->diffuse, "Make every material Lambertian (its diffuse colour kept)");
        app.add_option("--resolution", args->resolution, "Cube map N (a power of two; default: the scene's)");
        app.add_option("--sh-orders", *sh, "SH orders n (n^2 coefficients)")->capture_default_str();
        app.add_option("--haar-terms", *haar, "Haar lighting terms N")->capture_default_str();
        app.add_option("--eigen-terms", *eigen,
                       "Eigentransport terms d (one PCA basis of the largest; empty: no eigentransport rows)")
            ->capture_default_str();
        app.add_option("--triple-terms", *triple, "Wavelet triple product lighting terms N (empty: no triple-product rows)")->capture_default_str();
        app.add_option("--triple-normals", args->triple_normals,
                       "Triple product BRDF tables: R_n, normals at the texel centres of a 6 x R_n^2 cube")
            ->capture_default_str()
            ->check(CLI::Range(1, 64));
        app.add_option("--triple-views", args->triple_views,
                       "Triple product BRDF tables: R_v x R_v views per normal (1 for Lambertian BRDFs)")
            ->capture_default_str()
            ->check(CLI::Range(1, 64));
        app.add_option("--triple-brdf-terms", args->triple_brdf_terms,
                       "Triple product BRDF tables: M largest area-weighted Haar terms kept per slice")
            ->capture_default_str()
            ->check(CLI::Range(1, 1 << 20));
        app.add_option("--triple-lookup", *lookup,
                       "Triple product BRDF tables: bilinear (blend the 2x2 nearest normals x 2x2 nearest views) "
                       "or nearest (one slice, as Ng 2004)")
            ->check(CLI::IsMember({"bilinear", "nearest"}))
            ->capture_default_str();
        app.add_option("--rsl-lights", *rsl, "RSL counts K (default 10,30,60,100; with --many-light 10,30,100)");
        app.add_flag("--no-rsl", args->no_rsl, "Skip the RSL renderer (no field bake)");
        app.add_flag("--eigen-objects-basis", args->eigen_objects_basis,
                     "Fit the eigentransport basis to the objects' vertices only (every part but ground/floor); the "
                     "ground's vertices are projected onto it");
        app.add_flag("--no-ground", args->no_ground,
                     "Remove the parts named ground or floor before anything runs (the eigentransport paper's "
                     "ground bias); an error if there is none");
        app.add_option("--haar-drop", args->haar_drop, "Drop transport wavelets below this x the vertex's largest")
            ->capture_default_str();
        app.add_option("--width", args->width, "Image width")->capture_default_str();
        app.add_option("--height", args->height, "Image height")->capture_default_str();
        app.add_option("--repeats", args->repeats, "Frames timed per method (median)")->capture_default_str();
        app.add_flag("--quiet,-q", args->quiet, "No progress lines");
        auto* group = app.add_option_group("many lights",
            "--many-light: the same RSLs, light integrals and BRDF averages, only visibility changes "
            "(docs/BASELINES.md, \"Many lights\")");
        group->add_flag("--many-light", *many_light,
                        "Compare RSL with ray-traced and shadow-mapped visibility instead of SH/Haar PRT");
        group->add_option("--ray-samples", *rays, "S for the ray-traced rows: S x S stratified rays per vertex and light")
            ->capture_default_str();
        group->add_option("--ray-budget", many->ray_budget,
                          "Also a ray-traced row whose S fits this many rays per frame (0: none)")
            ->capture_default_str();
        group->add_option("--baseline-lights", many->baseline_lights, "K of the ray-traced and shadow-mapped rows")
            ->capture_default_str()
            ->check(CLI::Range(1, 1000));
        group->add_option("--gl-lights", *gl_lights, "K of the RSL rows on the GL path (empty: none)")
            ->capture_default_str();
        group->add_option("--shadow-maps", *maps, "Shadow-map resolutions of the GL rows (empty: none)")
            ->capture_default_str();
        group->add_option("--gl-ray-samples", *gl_rays,
                          "S for the GL ray-traced rows: the --ray-samples rays, traced in the GL vertex pass "
                          "(empty: none)")
            ->capture_default_str();
        group->add_option("--env-ray-samples", *env_rays,
                          "N of the env-rays rows: N rays per vertex, the map and the BRDF importance sampled "
                          "(empty: none)")
            ->capture_default_str();
        group->add_option("--receivers", many->receivers, "Parts left out of the objects' error")
            ->capture_default_str()
            ->delimiter(',');
        app.callback([&app, args, many, many_light, sh, haar, eigen, triple, lookup, rsl, rays, maps, gl_lights, gl_rays,
                      env_rays] {
            if (args->resolution != 0 && (args->resolution < 1 || args->resolution > kMaxCubeResolution))
                throw_error("--resolution {}: expected 1 to {} texels per cube-face edge", args->resolution,
                            kMaxCubeResolution);
            if (*many_light) {
                if (args->no_ground)  // the many-light rows keep the ground and measure the objects apart
                    throw_error("--no-ground is for the PRT baselines, not --many-light (see --receivers)");
                many->scene = args->scene;
                many->time = args->time;
                many->environment = args->environment;
                many->resolution = args->resolution;
                many->width = args->width, many->height = args->height;
                many->repeats = args->repeats;
                many->quiet = args->quiet;
                if (app.count("--output")) many->output = args->output;
                if (app.count("--rsl-lights")) many->rsl_lights = parse_list(*rsl, "--rsl-lights", true);
                if (args->no_rsl) many->rsl_lights.clear();
                many->ray_samples = parse_list(*rays, "--ray-samples", true);
                for (int s : many->ray_samples)
                    if (s > RenderOptions::kMaxRaySamples)
                        throw_error("--ray-samples: {} is above {}", s, RenderOptions::kMaxRaySamples);
                many->shadow_map_resolutions = parse_list(*maps, "--shadow-maps", true);
                for (int r : many->shadow_map_resolutions)
                    if (r < ShadowMapOptions::kMinResolution || r > ShadowMapOptions::kMaxResolution)
                        throw_error("--shadow-maps: {} is outside [{}, {}]", r, ShadowMapOptions::kMinResolution,
                                    ShadowMapOptions::kMaxResolution);
                many->gl_lights = parse_list(*gl_lights, "--gl-lights", true);
                many->gl_ray_samples = parse_list(*gl_rays, "--gl-ray-samples", true);
                for (int s : many->gl_ray_samples)
                    if (s > GpuRayOptions::kMaxSamplesPerSide)
                        throw_error("--gl-ray-samples: {} is above {}", s, GpuRayOptions::kMaxSamplesPerSide);
                many->env_ray_samples = parse_list(*env_rays, "--env-ray-samples", true);
                for (int n : many->env_ray_samples)
                    if (n > ManyLightExperiment::kMaxEnvRaySamples)
                        throw_error("--env-ray-samples: {} is above {}", n, ManyLightExperiment::kMaxEnvRaySamples);
                run_many_light_experiment(*many);
                return;
            }
            args->sh_orders = parse_list(*sh, "--sh-orders");
            for (int order : args->sh_orders)
                if (order > sh::kMaxOrder) throw_error("--sh-orders: order {} is above {}", order, sh::kMaxOrder);
            args->haar_terms = parse_list(*haar, "--haar-terms");
            args->eigen_terms = parse_list(*eigen, "--eigen-terms", true);
            args->triple_terms = parse_list(*triple, "--triple-terms", true);
            args->triple_lookup = *lookup == "nearest" ? TripleLookup::nearest : TripleLookup::bilinear;
            args->rsl_lights = parse_list(*rsl, "--rsl-lights");
            run_baselines_experiment(*args);
        });
    }});

}  // namespace
}  // namespace rsl::cli
