// Compare (RSL paper Figures 9 and 10): one frame rendered by the Embree
// ground truth (every cube-map texel, a shadow ray each) and by the RSL
// renderer with 10, 30 and 100 square lights, side by side, with the
// error image of each under it (false colour, one scale for all three:
// the largest error of the 10-light image). The relative L2 errors over
// vertices and over the image's pixels go into the labels and the notes.
//
// All four use the same cube map, the same fields and the same image
// formation, so the differences are the RSL approximation alone (lighting
// fit, square BRDF/visibility averages, VDT/PCA compression).
#include <chrono>

#include <fmt/format.h>
#include <cmath>

#include "tools/rsl/progress_display.h"
#include "src/formats/image_file.h"
#include "src/lightfit/scene_lights.h"
#include "demos/contact_sheet.h"
#include "demos/demo_runners.h"
#include "demos/demo_support.h"
#include "src/backend/make_renderer.h"
#include "src/core/error.h"
#include "src/render/render_setup.h"
#include "src/image/error_metrics.h"
#include "src/trace/ground_truth.h"

namespace rsl::demos {

namespace {
constexpr int kLightCounts[] = {10, 30, 100};
}  // namespace

DemoResult run_compare_demo(const DemoOptions& options) {
    namespace fs = std::filesystem;
    DemoResult result;
    result.name = "compare";
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, "compare/scene.json");
    RenderOptions render;
    render.environment_light_count = kLightCounts[0];
    const RenderSetup setup = prepare_render(scene, render, {.progress = cli::drawn_progress(options.progress), .field_cache = options.field_cache});
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());
    const float t = scene->animation.start;
    const int width = options.width > 0 ? options.width : 240;
    const int height = options.height > 0 ? options.height : 180;
    const PosedScene posed(*scene, t);

    FrameTiming truth_timing;
    truth_timing.time = t;
    auto begin = std::chrono::steady_clock::now();
    const GroundTruth truth(*scene, setup.environment_at(t), t);
    const VertexColors truth_colors = truth.shade_vertices();
    truth_timing.shade_seconds = seconds_between(begin, std::chrono::steady_clock::now());
    begin = std::chrono::steady_clock::now();
    const Image truth_image = form_frame(posed, *scene, t, truth_colors, width, height);
    truth_timing.image_seconds = seconds_between(begin, std::chrono::steady_clock::now());
    result.metrics["truth_seconds"] = truth_timing.shade_seconds;  // not a frame time: kept out of timings
    result.notes.push_back(fmt::format("ground truth: {} vertices x {} texels, {:.2f} s", scene->vertex_count(),
                                       truth.environment_sample_count(), truth_timing.shade_seconds));

    const fs::path folder = output_folder(options, result.name);
    ToneMap tone;
    tone.exposure = exposure_for(truth_image);
    std::vector<Image> top{truth_image}, bottom{Image(width, height, 3)};
    std::vector<std::string> top_labels{"ground truth"}, bottom_labels{"error (false colour)"};
    auto write = [&](const std::string& stem, const Image& image) {
        result.frames.push_back(folder / (stem + ".png"));
        write_png(result.frames.back(), image, tone);
    };
    write("truth", truth_image);
    std::vector<Image> images;
    std::vector<VertexColors> vertex_results;
    for (const int lights : kLightCounts) {
        FrameTiming timing;
        timing.time = t;
        begin = std::chrono::steady_clock::now();
        RenderOptions k_options = render;
        k_options.environment_light_count = lights;
        RslSet set =
            lights == kLightCounts[0] ? setup.environment_lights.first : fit_scene_lights(*setup.scene, setup.environment, lights);
        const std::unique_ptr<VertexRenderer> renderer =
            make_renderer(Backend::Cpu, *scene, std::move(set), setup.fields, k_options);
        timing.update_seconds = seconds_between(begin, std::chrono::steady_clock::now());  // fit + tables
        begin = std::chrono::steady_clock::now();
        renderer->set_time(t);
        vertex_results.push_back(renderer->shade());
        timing.shade_seconds = seconds_between(begin, std::chrono::steady_clock::now());
        begin = std::chrono::steady_clock::now();
        images.push_back(form_frame(posed, *scene, t, vertex_results.back(), width, height));
        timing.image_seconds = seconds_between(begin, std::chrono::steady_clock::now());
        result.timings.push_back(timing);
    }
    // One false-colour scale for all error images: the 10-light image's largest error.
    const float scale = float(compare_images(images.front(), truth_image).pixels.max_error);
    for (size_t k = 0; k < images.size(); ++k) {
        const int lights = kLightCounts[k];
        const ImageErrorReport pixels = compare_images(images[k], truth_image);
        const VertexErrorReport vertices = compare_vertex_colors(vertex_results[k], truth_colors);
        Image error = error_image(images[k], truth_image, scale);
        write(fmt::format("rsl_{:03d}", lights), images[k]);
        {
            const fs::path path = folder / fmt::format("error_{:03d}.png", lights);
            write_png(path, error);  // false colour is display-ready: no exposure
            result.frames.push_back(path);
        }
        // The sheet is tone-mapped with the truth's exposure: undo it for the error tiles.
        for (float& value : error.pixels) value *= std::exp2(-tone.exposure);
        top.push_back(images[k]), bottom.push_back(error);
        top_labels.push_back(fmt::format("RSL K={}", lights));
        bottom_labels.push_back(fmt::format("err {:.1f}% (H1 {:.0f}%)", 100 * pixels.pixels.relative_l2(),
                                            100 * pixels.relative_h1()));
        result.metrics[fmt::format("pixel_error_K{}", lights)] = pixels.pixels.relative_l2();
        result.metrics[fmt::format("vertex_error_K{}", lights)] = vertices.total.relative_l2();
        result.notes.push_back(fmt::format(
            "K={:3d}: relative L2 error {:.2f}% over pixels (H1 {:.1f}%), {:.2f}% over vertices; shading {:.1f} ms",
            lights, 100 * pixels.pixels.relative_l2(), 100 * pixels.relative_h1(),
            100 * vertices.total.relative_l2(), 1e3 * result.timings[k].shade_seconds));
    }
    std::vector<Image> tiles = top;
    tiles.insert(tiles.end(), bottom.begin(), bottom.end());
    std::vector<std::string> labels = top_labels;
    labels.insert(labels.end(), bottom_labels.begin(), bottom_labels.end());
    ContactSheetLayout layout;
    layout.columns = int(top.size());
    layout.label_color = Color(std::exp2(-tone.exposure));
    result.contact_sheet = folder / "contact_sheet.png";
    write_png(result.contact_sheet, make_contact_sheet(tiles, labels, layout), tone);
    return result;
}

}  // namespace rsl::demos
