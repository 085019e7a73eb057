#pragma once
// The scenes, environments and settings of `rsl bench render` and of the error
// table in docs/RESULTS.md (`rsl bench render-accuracy`), in one place so the
// numbers there can be reproduced.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/bench/bench.h"
#include "src/core/scene.h"

namespace rsl {

struct RenderBenchCase {
    std::string name;
    std::string scene_file;   // under BenchOptions::scenes
    bool needs_shared = false;
    int lights = 30;
    float time = 0;
};

// bunny on a plane, the robot, the kitchen at 30 RSLs (quick: the robot only).
std::vector<RenderBenchCase> render_speed_cases(bool quick);

// The precomputation settings the benchmarks and the table use: the
// resolutions of assets/scenes/default.json but for its 20 shells (SVDF 16²,
// 64 clusters × 6 vectors; OVDF 13 shells 0.4R…20R × 6×16² samples, 16² VDTs,
// 6 vectors), so that the fields bake in seconds on two cores. The scene files' full settings (the
// paper's) only make the fields more exact.
PrecomputeSettings bench_precompute();

// Loads the case's scene (from assets.scenes) with bench_precompute(); null
// when it needs the shared assets and they are absent.
std::shared_ptr<Scene> load_bench_scene(const RenderBenchCase& c, const bench::BenchOptions& assets);

struct AccuracyRow {
    std::string scene, environment, material;
    float time = 0;
    int lights = 0;
    size_t vertices = 0;
    double error = 0;        // renderer vs truth, per-vertex relative L2 (RGB)
    double objects_error = 0;  // the same over every part but the ground (object_errors)
    std::string worst_part;    // the object part of largest error, and that error
    double worst_part_error = 0;
    double light_error = -1;  // truth under the RSL reconstruction of the map vs truth (light approximation alone); -1: not measured
    double no_occluder_error = 0;  // renderer without the OVDF factor vs truth
    double truth_seconds = 0, render_seconds = 0;
    std::string settings = "bench";  // precompute: "bench" (bench_precompute()) or "scene" (the scene file's)
};

// Every row of the table (slow: one ground truth per scene × time ×
// environment × material). quick: the robot at t = 0 under grace only, K = 10, 30.
// Scenes, probes and the generated sun and sky come from `assets`' folders.
std::vector<AccuracyRow> render_accuracy_table(const bench::BenchOptions& assets, bool quick, bool progress = true);
// The goal rows: the glossy robot under grace at t = 0, 0.5, 1 with
// the scene file's own precompute settings (the paper's: 16 shells, 32² cube
// and VDTs, 8 vectors; fields from the scene's cache, baked once), K = 10, 30,
// 60, 100 (quick: t = 0, K = 30).
std::vector<AccuracyRow> render_accuracy_goal_rows(const bench::BenchOptions& assets, bool quick, bool progress = true);
nlohmann::json accuracy_row_json(const AccuracyRow& row);

}  // namespace rsl
