#include "tools/rsl/image_args.h"

#include <cmath>
#include <cstdio>

#include "src/core/error.h"

namespace rsl::cli {

void check_image_size(const std::optional<int>& width, const std::optional<int>& height, int samples) {
    if (width && (*width < 1 || *width > kMaxImageSide))
        throw_error("--width {}: expected 1 to {} pixels (leave it out for the scene camera's width)", *width,
                    kMaxImageSide);
    if (height && (*height < 1 || *height > kMaxImageSide))
        throw_error("--height {}: expected 1 to {} pixels (leave it out for the scene camera's height)", *height,
                    kMaxImageSide);
    if (samples < 1 || samples > kMaxSamplesPerSide)
        throw_error("--samples {}: expected 1 to {} (S×S primary rays per pixel)", samples, kMaxSamplesPerSide);
}

void check_time(const char* flag, float seconds) {
    if (!(std::abs(seconds) <= kMaxTimeSeconds))
        throw_error("{} {}: expected a time from {:g} to {:g} seconds", flag, seconds, -kMaxTimeSeconds,
                    kMaxTimeSeconds);
}

void check_exposure(float stops) {
    if (!(std::abs(stops) <= kMaxExposureStops))
        throw_error("--exposure {}: expected {:g} to {:g} stops (0: automatic)", stops, -kMaxExposureStops,
                    kMaxExposureStops);
}

std::vector<float> parse_frames(const std::string& text) {
    float a = 0, b = 0, step = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%f:%f:%f%c", &a, &b, &step, &tail) != 3 || !(step > 0) || !(b >= a))
        throw_error("--frames '{}': expected START:END:STEP with STEP > 0 and END ≥ START", text);
    check_time("--frames START", a);
    check_time("--frames END", b);
    // Counted in double before anything is allocated: a tiny step asks for billions.
    const double count = std::floor((double(b) - double(a)) / double(step) + 1e-4) + 1;
    if (!(count <= double(kMaxFrames)))
        throw_error("--frames '{}': {:.0f} frames, at most {} in one run", text, count, kMaxFrames);
    std::vector<float> times;
    for (int i = 0;; ++i) {
        const float t = a + float(i) * step;
        if (t > b + 1e-4f * step || times.size() >= size_t(count)) break;
        times.push_back(t);
    }
    return times;
}

}  // namespace rsl::cli
