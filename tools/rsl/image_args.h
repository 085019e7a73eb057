#pragma once
// The image and time flags that `rsl render` and `rsl truth` share, checked
// before anything is loaded: a NaN time renders black, an image past the
// limits runs for minutes before writing it fails (issue 43).
#include <optional>
#include <string>
#include <vector>

#include "src/core/scene_limits.h"

namespace rsl::cli {

// As the scene file's camera and the API (src/core/scene_limits.h).
inline constexpr int kMaxImageSide = ::rsl::kMaxImageSide;
inline constexpr int kMaxSamplesPerSide = ::rsl::kMaxPixelSamplesPerSide;
// Times in seconds: about 11 days of animation; float time keeps millisecond steps below it.
inline constexpr float kMaxTimeSeconds = 1e6f;
// PNG exposure in stops: 2^±64 maps any finite radiance into or out of range.
inline constexpr float kMaxExposureStops = 64.0f;
// Numbered frames one `--frames` run writes.
inline constexpr long long kMaxFrames = 100000;

// Throws rsl::Error unless each given side is 1..kMaxImageSide and samples is 1..kMaxSamplesPerSide.
void check_image_size(const std::optional<int>& width, const std::optional<int>& height, int samples);

// Throws rsl::Error naming `flag` unless |seconds| ≤ kMaxTimeSeconds (so not NaN or infinite).
void check_time(const char* flag, float seconds);

// Throws rsl::Error unless |stops| ≤ kMaxExposureStops (so not NaN or infinite).
void check_exposure(float stops);

// "A:B:STEP" → the times A, A + STEP, … ≤ B (inclusive within rounding);
// each finite and within kMaxTimeSeconds, at most kMaxFrames of them.
std::vector<float> parse_frames(const std::string& text);

}  // namespace rsl::cli
