#pragma once
// What every demo shares: loading its scene with the demo's precompute
// settings, the frame clock, image formation with a fixed exposure, and the
// outputs (PNG sequence, contact sheet, MP4).
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "demos/demo.h"
#include "src/backend/render_session.h"
#include "src/core/image.h"
#include "src/core/scene.h"
#include "src/render/render_options.h"
#include "src/rays/posed_scene.h"
#include "src/formats/vertex_colors.h"

namespace rsl::demos {

// --quick: precompute and environment small enough for a test (docs/DEMOS.md).
void apply_quick_settings(Scene& scene);
inline constexpr int kQuickLights = 8;

// The demo's scene file (relative to the demos folder), quick settings applied.
std::shared_ptr<Scene> load_demo_scene(const DemoOptions& options, const std::string& relative_path);
std::filesystem::path demos_folder(const DemoOptions& options);
std::filesystem::path output_folder(const DemoOptions& options, const std::string& demo);

// `frames` times spread evenly over the scene's animation range [start, end):
// the range is a loop, so the last frame does not repeat the first.
std::vector<float> frame_times(const Scene& scene, int frames);

// Every demo frame's background: dark and opaque.
ImageFormationOptions demo_formation();
// The image of per-vertex colours from the scene camera at t, on demo_formation()'s background.
Image form_frame(const PosedScene& posed, const Scene& scene, float t, const VertexColors& colors, int width,
                 int height);

// out = Σ w_i · in_i over vertices (all inputs describe the same vertices).
void weighted_sum(VertexColors& out, const std::vector<const VertexColors*>& inputs, const std::vector<float>& weights);

// Exposure (stops) mapping the 99th luminance percentile of the image to 0.7 (headroom: a
// lit white floor stays grey enough to show the shadows on it).
float exposure_for(const Image& image);

// Writes frames as out/frame_NNNN.png with the exposure of the first one,
// keeps a reduced copy of each for the contact sheet, and at the end writes
// the sheet (at most `sheet_tiles` frames, evenly picked) and the MP4.
class FrameSequence {
public:
    FrameSequence(std::filesystem::path folder, int sheet_columns = 4, int sheet_tiles = 8);
    void set_exposure(float stops) { exposure_ = stops, exposure_fixed_ = true; }
    float exposure() const { return exposure_; }
    // Returns the written path.
    std::filesystem::path add(const Image& frame, const std::string& label);
    // Contact sheet (contact_sheet.png) and, with ffmpeg on PATH, NAME.mp4.
    void finish(DemoResult& result, float fps);

private:
    std::filesystem::path folder_;
    int columns_, max_tiles_;
    float exposure_ = 0;
    bool exposure_fixed_ = false;
    std::vector<Image> tiles_;
    std::vector<std::string> labels_;
    std::vector<std::filesystem::path> written_;
};

// Full path of an executable found on PATH, or empty.
std::filesystem::path find_on_path(const std::string& program);
// Encodes the PNG frames named by `pattern` (printf style, e.g. folder/frame_%04d.png,
// numbered from 0) into an H.264 MP4 with ffmpeg, atomically; throws on failure.
void encode_mp4(const std::filesystem::path& ffmpeg, const std::filesystem::path& pattern, float fps,
                const std::filesystem::path& mp4);

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b);

}  // namespace rsl::demos

#include <functional>

namespace rsl::demos {

// The frame loop every animated demo runs: for each frame time, the frame
// is edited, shaded and formed, written, and the label returned by `label` goes on
// its contact-sheet tile.
struct SequenceSpec {
    std::string name;
    int default_frames = 12;
    int default_width = 320, default_height = 240;
    // Edits before frame f is shaded (timed as the frame's update); may be empty.
    std::function<void(int frame, float t)> update;
    std::function<std::string(int frame, float t)> label;  // empty: "t=…s"
};
// Per frame: `update`, the session's shade at t and its own image
// (per-pixel shadows and highlights, as `rsl render` forms it).
void render_sequence(const SequenceSpec& spec, const DemoOptions& options, RenderSession& session,
                     DemoResult& result);

// A demo that plays its scene's own animation (robot, walker): the scene at
// `relative_path`, its CPU session at the demo's light count (the setup
// timed), render_sequence, and one note from `note` (the scene, the lights).
DemoResult run_scene_sequence(const DemoOptions& options, const std::string& name, const std::string& relative_path,
                              const std::function<std::string(const Scene& scene, int lights)>& note);

}  // namespace rsl::demos
