#pragma once
// How `rsl render` and `rsl truth` write their frames (docs/COMMANDS.md):
// `-o NAME.exr` writes the EXR and a PNG preview beside it, `-o NAME.png` the
// PNG alone; a --frames run numbers each frame NAME.NNNN.ext, tone-maps every
// frame with one exposure (so that the frames compare and play alike) and can
// join the PNGs into an animation: an animated PNG rsl writes itself, or an
// MP4 through ffmpeg.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "src/formats/animated_png.h"
#include "src/formats/image_file.h"
#include "src/core/scene.h"
#include "src/image/image_formation.h"

namespace rsl::cli {

// out.exr, frame 7 → out.0007.exr
std::filesystem::path numbered(const std::filesystem::path& path, int frame);

// Throws rsl::Error unless `output` names an .exr or a .png image.
void check_image_output(const std::string& output);
// The files one frame's image writes: the .exr and its .png preview, or the .png alone.
std::vector<std::filesystem::path> image_files(const std::filesystem::path& output);

// What fills the pixels no part covers: nothing (black, alpha 0), a colour, or the environment.
struct Background {
    enum class Kind { None, Color, Environment } kind = Kind::None;
    Color color{0};
};
// "environment", or "R,G,B" or "R G B" (each 0 to kMaxRadiance); throws rsl::Error naming `flag` otherwise.
Background parse_background(const std::string& text, const char* flag = "--background");

// The environment drawn behind the scene (--background environment): the
// scene's map(s) at kResolution texels per cube-face edge, finer than the
// lighting's, blended and turned as at each frame's time. The suns are lights
// of their own, not in the map, and do not show.
class EnvironmentBackdrop {
public:
    static constexpr int kResolution = 256;
    explicit EnvironmentBackdrop(const Scene& scene);
    // Fills the uncovered share of `image` (RGBA, as formed through `camera`).
    void fill(Image& image, const PinholeCamera& camera, int samples_per_side, float t) const;

private:
    const Scene& scene_;
    CubeMap first_, second_;
};

// One run's frames: their paths, one exposure for all of them, the animation.
class FrameOutput {
public:
    // `frame_seconds`: the frames' spacing in scene time, also the
    // animation's delay. `exposure` in stops, 0: automatic (for a sequence,
    // the first frame's for every frame). `animation` empty: none, else .png
    // (animated PNG) or .mp4 (ffmpeg; refused here when ffmpeg is not on PATH).
    FrameOutput(std::filesystem::path output, size_t frames, double frame_seconds, float exposure,
                std::filesystem::path animation);

    size_t frames() const { return frames_; }
    std::filesystem::path image_path(size_t frame) const;  // the -o path, numbered when frames > 1
    // Every file the run writes (the images and the animation), for check_outputs_apart.
    std::vector<std::filesystem::path> files() const;
    // Writes frame `frame`'s image (EXR + PNG, or PNG); frames come in order.
    void write(size_t frame, const Image& image);
    // The exposure every frame of a sequence gets, once the first is written.
    std::optional<float> sequence_exposure() const { return sequence_exposure_; }
    // Writes the animation, if one was asked for; returns its path (empty: none).
    std::filesystem::path finish();

private:
    std::filesystem::path output_, animation_;
    size_t frames_;
    double frame_seconds_;
    float exposure_;
    std::optional<float> sequence_exposure_;
    std::unique_ptr<AnimatedPng> apng_;
};

}  // namespace rsl::cli
