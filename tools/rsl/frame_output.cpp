#include "tools/rsl/frame_output.h"

#include <cmath>
#include <sstream>
#include <string>

#include <fmt/core.h>

#include "demos/demo_support.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "src/formats/scene_environment.h"

namespace rsl::cli {

namespace fs = std::filesystem;

fs::path numbered(const fs::path& path, int frame) {
    fs::path result = path;
    result.replace_filename(fmt::format("{}.{:04d}{}", path.stem().string(), frame, path.extension().string()));
    return result;
}

void check_image_output(const std::string& output) {
    const std::string extension = fs::path(output).extension().string();
    if (extension != ".exr" && extension != ".png")
        throw_error("-o {}: expected an .exr path (a .png preview is written beside it) or a .png path (the "
                    "tone-mapped image alone)",
                    output);
}

std::vector<fs::path> image_files(const fs::path& output) {
    if (output.extension() == ".png") return {output};
    return {output, fs::path(output).replace_extension(".png")};
}

Background parse_background(const std::string& text, const char* flag) {
    Background background;
    if (text.empty()) return background;
    if (text == "environment") {
        background.kind = Background::Kind::Environment;
        return background;
    }
    // R,G,B (or R G B, as three arguments)
    std::string spaced = text;
    for (char& c : spaced) c = c == ',' ? ' ' : c;
    std::istringstream in(spaced);
    std::vector<float> rgb;
    bool parsed = true;
    for (std::string item; in >> item;) {
        size_t used = 0;
        try {
            rgb.push_back(std::stof(item, &used));
        } catch (const std::exception&) {
            parsed = false;
        }
        parsed = parsed && used == item.size();
    }
    if (!parsed || rgb.size() != 3)
        throw_error("{} {}: expected environment, or a colour R,G,B (three radiances, e.g. 0.2,0.2,0.25)", flag, text);
    for (const float value : rgb)  // a NaN background is a NaN in every uncovered pixel
        if (!(value >= 0 && value <= kMaxRadiance))
            throw_error("{} {}: expected radiances from 0 to {:g} (finite)", flag, text, kMaxRadiance);
    background.kind = Background::Kind::Color;
    background.color = Color(rgb[0], rgb[1], rgb[2]);
    return background;
}

EnvironmentBackdrop::EnvironmentBackdrop(const Scene& scene)
    : scene_(scene), first_(scene_environment_map(scene, kResolution)) {
    if (!scene.environment.second_file.empty()) second_ = scene_environment_map(scene, kResolution, true);
}

void EnvironmentBackdrop::fill(Image& image, const PinholeCamera& camera, int samples_per_side, float t) const {
    const Mat3 to_map = glm::transpose(scene_.environment.rotation_at(t));
    if (scene_.environment.second_file.empty()) {
        fill_environment_background(image, camera, samples_per_side, first_, to_map);
    } else {
        fill_environment_background(image, camera, samples_per_side,
                                    blend_environments(first_, second_, scene_.environment.blend_weight_at(t)), to_map);
    }
}

FrameOutput::FrameOutput(fs::path output, size_t frames, double frame_seconds, float exposure, fs::path animation)
    : output_(std::move(output)), animation_(std::move(animation)), frames_(frames), frame_seconds_(frame_seconds),
      exposure_(exposure) {
    if (animation_.empty()) return;
    const std::string extension = animation_.extension().string();
    if (extension != ".png" && extension != ".mp4")
        throw_error("--animation {}: expected a .png (an animated PNG rsl writes itself) or an .mp4 (through ffmpeg)",
                    animation_.string());
    if (frames_ < 2) throw_error("--animation {}: needs a sequence (--frames START:END:STEP)", animation_.string());
    if (extension == ".mp4" && demos::find_on_path("ffmpeg").empty())
        throw_error("--animation {}: ffmpeg is not on PATH (install it, e.g. apt install ffmpeg), or give a .png for "
                    "an animated PNG, which needs nothing else",
                    animation_.string());
}

fs::path FrameOutput::image_path(size_t frame) const {
    return frames_ > 1 ? numbered(output_, int(frame)) : output_;
}

std::vector<fs::path> FrameOutput::files() const {
    std::vector<fs::path> files;
    for (size_t f = 0; f < frames_; ++f)
        for (const fs::path& file : image_files(image_path(f))) files.push_back(file);
    if (!animation_.empty()) files.push_back(animation_);
    return files;
}

void FrameOutput::write(size_t frame, const Image& image) {
    RSL_CHECK_LT(frame, frames_);
    ToneMap tone{exposure_, exposure_ == 0.0f};
    if (frames_ > 1) {
        // One exposure for the whole sequence: automatic exposure per frame
        // would change the brightness from frame to frame.
        if (!sequence_exposure_) sequence_exposure_ = exposure_ != 0.0f ? exposure_ : auto_exposure_stops(image);
        tone = ToneMap{*sequence_exposure_, false};
    }
    const fs::path path = image_path(frame);
    if (path.extension() == ".png") write_png(path, image, tone);
    else write_exr_and_png(path, image, tone);
    if (animation_.extension() == ".png") {
        if (!apng_) apng_ = std::make_unique<AnimatedPng>(image.width, image.height, image.channels);
        apng_->add_frame(tone_mapped_pixels(image, tone));
    }
}

fs::path FrameOutput::finish() {
    if (animation_.empty()) return {};
    if (animation_.extension() == ".png") {
        RSL_CHECK(apng_ && apng_->frame_count() == frames_);
        write_animated_png(animation_, *apng_, frame_seconds_);
    } else {
        // The frames' PNGs, numbered from 0; a % in the name is ffmpeg's pattern character.
        const fs::path png = fs::path(output_).replace_extension(".png");
        std::string stem;
        for (const char c : png.stem().string()) stem += c == '%' ? std::string("%%") : std::string(1, c);
        demos::encode_mp4(demos::find_on_path("ffmpeg"), png.parent_path() / (stem + ".%04d.png"),
                          float(1.0 / frame_seconds_), animation_);
    }
    return animation_;
}

}  // namespace rsl::cli
