#include "src/core/texture.h"

#include <cmath>

namespace rsl {

int wrap_texel(int i, int n, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge: return i < 0 ? 0 : (i >= n ? n - 1 : i);
        case TextureWrap::MirroredRepeat: {
            const int period = 2 * n;
            int m = i % period;
            if (m < 0) m += period;
            return m < n ? m : period - 1 - m;
        }
        case TextureWrap::Repeat:
        default: {
            const int m = i % n;
            return m < 0 ? m + n : m;
        }
    }
}

Color Texture::sample(const Vec2& uv) const {
    // Texel space with centers on integers; floor in double so that large
    // repeat counts keep their fractional part.
    const double x = double(uv.x) * image.width - 0.5, y = double(uv.y) * image.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const float wx = float(x - fx), wy = float(y - fy);
    // Indices are reduced first so that huge coordinates cannot overflow int.
    const auto reduce = [](double f, int n) { return int(std::fmod(f, 2.0 * n)); };
    const int x0 = reduce(fx, image.width), y0 = reduce(fy, image.height);
    const int i0 = wrap_texel(x0, image.width, wrap_s), i1 = wrap_texel(x0 + 1, image.width, wrap_s);
    const int j0 = wrap_texel(y0, image.height, wrap_t), j1 = wrap_texel(y0 + 1, image.height, wrap_t);
    const Color top = glm::mix(image.rgb(i0, j0), image.rgb(i1, j0), wx);
    const Color bottom = glm::mix(image.rgb(i0, j1), image.rgb(i1, j1), wx);
    return glm::mix(top, bottom, wy);
}

Color Texture::sample_nearest(const Vec2& uv) const {
    const double x = std::floor(double(uv.x) * image.width), y = std::floor(double(uv.y) * image.height);
    const int i = wrap_texel(int(std::fmod(x, 2.0 * image.width)), image.width, wrap_s);
    const int j = wrap_texel(int(std::fmod(y, 2.0 * image.height)), image.height, wrap_t);
    return image.rgb(i, j);
}

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace rsl
