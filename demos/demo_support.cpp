#include "demos/demo_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <fmt/format.h>

#include "demos/contact_sheet.h"
#include "tools/rsl/progress_display.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "src/formats/scene_file.h"
#include "src/image/image_formation.h"

namespace rsl::demos {

namespace fs = std::filesystem;

void apply_quick_settings(Scene& scene) {
    PrecomputeSettings& p = scene.precompute;
    p.svdf_resolution = 8;
    p.svdf_clusters = 16;
    p.svdf_vectors = 4;
    p.svdf_supersampling = 1;
    p.ovdf_shells = 4;
    p.ovdf_cube_resolution = 8;
    p.ovdf_vdt_resolution = 8;
    p.ovdf_vectors = 4;
    scene.environment.resolution = std::min(scene.environment.resolution, 8);
}

fs::path demos_folder(const DemoOptions& options) {
    return options.demos_dir.empty() ? fs::path(RSL_SOURCE_DIR) / "demos" : options.demos_dir;
}

fs::path output_folder(const DemoOptions& options, const std::string& demo) {
    return options.out_dir.empty() ? fs::path("out") / "demos" / demo : options.out_dir;
}

std::shared_ptr<Scene> load_demo_scene(const DemoOptions& options, const std::string& relative_path) {
    auto scene = std::make_shared<Scene>(load_scene(demos_folder(options) / relative_path));
    if (options.quick) apply_quick_settings(*scene);
    return scene;
}

std::vector<float> frame_times(const Scene& scene, int frames) {
    RSL_CHECK_GE(frames, 1);
    const float start = scene.animation.start, length = scene.animation.end - scene.animation.start;
    std::vector<float> times(frames);
    for (int f = 0; f < frames; ++f) times[f] = start + length * float(f) / float(frames);
    return times;
}

ImageFormationOptions demo_formation() {
    ImageFormationOptions formation;
    formation.opaque_background = true;
    formation.background = Color(0.015f, 0.016f, 0.02f);
    return formation;
}

Image form_frame(const PosedScene& posed, const Scene& scene, float t, const VertexColors& colors, int width,
                 int height) {
    return form_image(posed, PinholeCamera::at_time(scene.camera, t, width, height), colors, demo_formation());
}

void weighted_sum(VertexColors& out, const std::vector<const VertexColors*>& inputs, const std::vector<float>& weights) {
    RSL_CHECK_EQ(inputs.size(), weights.size());
    for (size_t p = 0; p < out.parts.size(); ++p) {
        std::vector<Color>& dst = out.parts[p];
        std::fill(dst.begin(), dst.end(), Color(0));
        for (size_t i = 0; i < inputs.size(); ++i) {
            const std::vector<Color>& src = inputs[i]->parts[p];
            RSL_CHECK_EQ(src.size(), dst.size());
            for (size_t v = 0; v < dst.size(); ++v) dst[v] += weights[i] * src[v];
        }
    }
}

float exposure_for(const Image& image) {
    std::vector<float> lum;
    lum.reserve(size_t(image.width) * image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) lum.push_back(luminance(image.rgb(x, y)));
    const size_t k = size_t(0.99 * double(lum.size() - 1));
    std::nth_element(lum.begin(), lum.begin() + k, lum.end());
    return lum[k] > 0.0f ? std::log2(0.7f / lum[k]) : 0.0f;
}

FrameSequence::FrameSequence(fs::path folder, int sheet_columns, int sheet_tiles)
    : folder_(std::move(folder)), columns_(sheet_columns), max_tiles_(sheet_tiles) {}

fs::path FrameSequence::add(const Image& frame, const std::string& label) {
    if (!exposure_fixed_) set_exposure(exposure_for(frame));
    const fs::path path = folder_ / fmt::format("frame_{:04d}.png", written_.size());
    ToneMap tone;
    tone.exposure = exposure_;
    write_png(path, frame, tone);
    written_.push_back(path);
    // Sheet tiles stay at most ~320 pixels wide so a sheet of 4 columns fits a page.
    tiles_.push_back(downsample(frame, std::max(1, (frame.width + 319) / 320)));
    labels_.push_back(label);
    return path;
}

void FrameSequence::finish(DemoResult& result, float fps) {
    RSL_CHECK(!tiles_.empty());
    result.frames = written_;
    std::vector<Image> tiles;
    std::vector<std::string> labels;
    const size_t count = std::min(tiles_.size(), size_t(max_tiles_));
    for (size_t i = 0; i < count; ++i) {
        const size_t f = i * tiles_.size() / count;  // evenly spread, first frame included
        tiles.push_back(tiles_[f]);
        labels.push_back(labels_[f]);
    }
    ContactSheetLayout layout;
    layout.columns = columns_;
    layout.label_color = Color(std::exp2(-exposure_));
    ToneMap tone;
    tone.exposure = exposure_;
    result.contact_sheet = folder_ / "contact_sheet.png";
    write_png(result.contact_sheet, make_contact_sheet(tiles, labels, layout), tone);
    const fs::path ffmpeg = find_on_path("ffmpeg");
    if (!ffmpeg.empty() && written_.size() > 1) {
        result.mp4 = folder_ / (result.name + ".mp4");
        encode_mp4(ffmpeg, folder_ / "frame_%04d.png", fps, result.mp4);
    } else if (ffmpeg.empty()) {
        result.notes.push_back("ffmpeg not found on PATH: no MP4 written");
    }
}

fs::path find_on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return {};
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        const fs::path candidate = fs::path(dir) / program;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) &&
            (fs::status(candidate, ec).permissions() & fs::perms::owner_exec) != fs::perms::none)
            return candidate;
    }
    return {};
}

namespace {
// Single quotes for /bin/sh, with embedded single quotes escaped.
std::string shell_quote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}
}  // namespace

void encode_mp4(const fs::path& ffmpeg, const fs::path& pattern, float fps, const fs::path& mp4) {
    write_atomically(mp4, [&](const fs::path& tmp) {
        // Even dimensions (yuv420p needs them) by padding one pixel if needed.
        const std::string command = fmt::format(
            "{} -y -loglevel error -framerate {} -start_number 0 -i {} -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 "
            "-pix_fmt yuv420p -f mp4 {}",
            shell_quote(ffmpeg.string()), fps, shell_quote(pattern.string()),
            shell_quote(tmp.string()));
        if (std::system(command.c_str()) != 0) throw_file_error(mp4, "ffmpeg failed: {}", command);
    });
}

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

}  // namespace rsl::demos

namespace rsl::demos {

void render_sequence(const SequenceSpec& spec, const DemoOptions& options, RenderSession& session,
                     DemoResult& result) {
    const Scene& scene = session.scene();
    const int frames = options.frames > 0 ? options.frames : spec.default_frames;
    const int width = options.width > 0 ? options.width : spec.default_width;
    const int height = options.height > 0 ? options.height : spec.default_height;
    const std::vector<float> times = frame_times(scene, frames);
    FrameSequence sequence(output_folder(options, spec.name));
    for (size_t f = 0; f < times.size(); ++f) {
        const float t = times[f];
        FrameTiming timing;
        timing.time = t;
        const auto begin = std::chrono::steady_clock::now();
        if (spec.update) spec.update(int(f), t);
        const auto edited = std::chrono::steady_clock::now();
        session.shade(t);
        const auto shaded = std::chrono::steady_clock::now();
        const Image image = session.image(session.camera(width, height), demo_formation());
        timing.update_seconds = seconds_between(begin, edited);
        timing.shade_seconds = seconds_between(edited, shaded);
        timing.image_seconds = seconds_between(shaded, std::chrono::steady_clock::now());
        const std::string label = spec.label ? spec.label(int(f), t) : fmt::format("t={:.2f}s", t);
        const fs::path path = sequence.add(image, label);
        result.timings.push_back(timing);
        if (options.progress)
            fmt::print("{} frame {}/{} t={:.3f}: update {:.1f} ms, shading {:.1f} ms, image {:.1f} ms -> {}\n",
                       spec.name, f + 1, times.size(), t, 1e3 * timing.update_seconds, 1e3 * timing.shade_seconds,
                       1e3 * timing.image_seconds, path.string());
    }
    // Real time: the frames span the animation range.
    const float length = scene.animation.end - scene.animation.start;
    sequence.finish(result, length > 0 ? float(frames) / length : 12.0f);
}

DemoResult run_scene_sequence(const DemoOptions& options, const std::string& name, const std::string& relative_path,
                              const std::function<std::string(const Scene& scene, int lights)>& note) {
    DemoResult result;
    result.name = name;
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<Scene> scene = load_demo_scene(options, relative_path);
    RenderOptions render;
    if (options.quick) render.environment_light_count = kQuickLights;
    RenderSession session(scene, render, Backend::Cpu,
                          {.progress = cli::drawn_progress(options.progress), .field_cache = options.field_cache});
    result.setup_seconds = seconds_between(start, std::chrono::steady_clock::now());
    SequenceSpec spec;
    spec.name = result.name;
    render_sequence(spec, options, session, result);
    result.notes.push_back(note(*scene, int(session.renderer().stats().lights)));
    return result;
}

}  // namespace rsl::demos
