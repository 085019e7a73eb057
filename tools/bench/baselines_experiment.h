#pragma once
// `rsl baselines` as a function: one static frame of a scene rendered with
// every method against the ground truth (docs/BASELINES.md): SH PRT with 9,
// 25 and 100 coefficients, Haar PRT with N = 20, 30, 60, 100 lighting terms,
// eigentransport with d = 16, 48, 128 terms, the wavelet triple product with
// N = 80, 320, the RSL renderer with K = 10, 30, 60, 100 lights. Environment
// light only (local lights off for every method: the baselines have none).
#include <string>
#include <vector>

#include "tools/baselines/triple.h"

namespace rsl {

struct BaselinesExperiment {
    std::string scene;                      // scene file (.json, .gltf/.glb, .obj)
    std::string output = "out/baselines";   // folder for the table and figures
    std::string environment;                // a probe instead of the scene's; empty: the scene's
    float time = 0;
    bool diffuse = false;  // every material Lambertian (its diffuse colour kept)
    bool no_rsl = false;   // skip the RSL renderer (no field bake)
    bool no_ground = false;  // remove the parts named ground or floor first (eigentransport's basis bias)
    bool quiet = false;    // no progress lines on stderr
    int resolution = 0;    // cube map N; 0: the scene's
    int width = 320, height = 240, repeats = 5;
    float haar_drop = 1e-3f;  // drop transport wavelets below this × the vertex's largest
    std::vector<int> sh_orders{3, 5, 10}, haar_terms{20, 30, 60, 100}, rsl_lights{10, 30, 60, 100};
    std::vector<int> eigen_terms{16, 48, 128};  // empty: no eigentransport rows
    bool eigen_objects_basis = false;  // fit the eigentransport basis to the objects' rows only (not a ground's)
    // Wavelet triple product (tools/baselines/triple.h): lighting terms N, and
    // the BRDF tables' normals R_n (6·R_n²), views R_v (R_v²) and terms M per
    // slice, and how a vertex finds its slice (bilinear blend or nearest).
    std::vector<int> triple_terms{80, 320};
    int triple_normals = 8, triple_views = 8, triple_brdf_terms = 256;
    TripleLookup triple_lookup = TripleLookup::bilinear;
};

// Runs every method and writes OUTPUT/table.md, results.json, sheet.png
// (images side by side), error_plot.png (error against the number of terms)
// and one EXR + PNG per method; prints the table.
void run_baselines_experiment(const BaselinesExperiment& experiment);

}  // namespace rsl
