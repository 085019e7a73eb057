#pragma once
// `rsl baselines SCENE --many-light` as a function (docs/BASELINES.md, "Many
// lights"): what a user would pick instead of precomputed fields. One static
// frame shaded with the same RSLs, light integrals and BRDF-SAT averages, the
// visibility factor alone changing:
//   rsl     — the fields (SVDF × Π OVDF), K = 10, 30, 100 lights, on the
//             CPU and (rsl-gl) on the GL path;
//   rays    — S×S stratified shadow rays per vertex and light (S = 1, 2, 4),
//             Embree packets on every core, no precomputation; rays-gl: the
//             same rays traced in the GL vertex pass (a BVH in a compute shader);
//   budget  — the same with S set per frame from a fixed ray budget;
//   shadow maps (GL) — one orthographic depth map per light, filtered with a
//             kernel sized to the square's angular size;
//   env-rays — no lights at all: N rays per vertex, the map and the BRDF
//             importance sampled (src/trace/environment_rays.h); it
//             converges to the truth as N grows.
// Each row: error against the ground truth (all vertices, the objects, the
// worst part, the image) and the frame time, all from one run. Environment
// light only (local lights off for every method and for the truth).
#include <cstdint>
#include <string>
#include <vector>

namespace rsl {

struct ManyLightExperiment {
    std::string scene;                       // scene file (.json, .gltf/.glb, .obj)
    std::string output = "out/many_light";   // folder for the table and figures
    std::string environment;                 // a probe instead of the scene's; empty: the scene's
    float time = 0;
    bool quiet = false;
    int resolution = 0;                      // cube map N; 0: the scene's
    int width = 320, height = 240;
    int repeats = 3;                         // frames timed per method (median)
    std::vector<int> rsl_lights{10, 30, 100};
    int baseline_lights = 30;                // K of the ray-traced and shadow-mapped rows
    std::vector<int> ray_samples{1, 2, 4};   // S: S×S rays per vertex and light
    uint64_t ray_budget = 0;                 // rays per frame for the budget row; 0: no such row
    std::vector<int> gl_lights{30};          // K of the RSL rows on the GL path (empty: none)
    std::vector<int> shadow_map_resolutions{256, 1024};  // GL shadow-map rows (empty: none)
    std::vector<int> gl_ray_samples{1, 2};   // S of the GL ray-traced rows (empty: none)
    std::vector<int> env_ray_samples{1, 4, 16, 64, 256};  // N of the env-rays rows (empty: none)
    static constexpr int kMaxEnvRaySamples = 1024;
    std::vector<std::string> receivers{"ground", "floor"};  // parts left out of the objects' error
};

// Runs every method and writes OUTPUT/table.md, results.json, pareto.png
// (error against frame time, one curve per method), sheet.png and one
// EXR + PNG per method; prints the table.
void run_many_light_experiment(const ManyLightExperiment& experiment);

}  // namespace rsl
