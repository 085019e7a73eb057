// Non-standard 2D Haar transform per cube face and the area-weighted N-term
// lighting approximation of Ng et al. 2003.
#include "tools/baselines/haar.h"

#include <algorithm>
#include <cmath>

#include "src/core/error.h"

namespace rsl::haar {

bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

namespace {

void check_resolution(int n) {
    if (!is_power_of_two(n)) throw_error("Haar transform needs a power-of-two face resolution, got {}", n);
}

}  // namespace

void forward_face(float* data, int n, int channels, float* scratch) {
    check_resolution(n);
    for (int side = n; side > 1; side /= 2) {
        const int half = side / 2;
        for (int y = 0; y < half; ++y)
            for (int x = 0; x < half; ++x)
                for (int c = 0; c < channels; ++c) {
                    const float a = data[((2 * y) * n + 2 * x) * channels + c];
                    const float b = data[((2 * y) * n + 2 * x + 1) * channels + c];
                    const float d0 = data[((2 * y + 1) * n + 2 * x) * channels + c];
                    const float d1 = data[((2 * y + 1) * n + 2 * x + 1) * channels + c];
                    scratch[(y * n + x) * channels + c] = 0.5f * (a + b + d0 + d1);
                    scratch[(y * n + x + half) * channels + c] = 0.5f * (a - b + d0 - d1);
                    scratch[((y + half) * n + x) * channels + c] = 0.5f * (a + b - d0 - d1);
                    scratch[((y + half) * n + x + half) * channels + c] = 0.5f * (a - b - d0 + d1);
                }
        for (int y = 0; y < side; ++y)
            std::copy_n(scratch + size_t(y) * n * channels, size_t(side) * channels, data + size_t(y) * n * channels);
    }
}

void inverse_face(float* data, int n, int channels, float* scratch) {
    check_resolution(n);
    for (int side = 2; side <= n; side *= 2) {
        const int half = side / 2;
        for (int y = 0; y < half; ++y)
            for (int x = 0; x < half; ++x)
                for (int c = 0; c < channels; ++c) {
                    const float s = data[(y * n + x) * channels + c];
                    const float h = data[(y * n + x + half) * channels + c];
                    const float v = data[((y + half) * n + x) * channels + c];
                    const float g = data[((y + half) * n + x + half) * channels + c];
                    scratch[((2 * y) * n + 2 * x) * channels + c] = 0.5f * (s + h + v + g);
                    scratch[((2 * y) * n + 2 * x + 1) * channels + c] = 0.5f * (s - h + v - g);
                    scratch[((2 * y + 1) * n + 2 * x) * channels + c] = 0.5f * (s + h - v - g);
                    scratch[((2 * y + 1) * n + 2 * x + 1) * channels + c] = 0.5f * (s - h - v + g);
                }
        for (int y = 0; y < side; ++y)
            std::copy_n(scratch + size_t(y) * n * channels, size_t(side) * channels, data + size_t(y) * n * channels);
    }
}

void forward_cube(float* data, int n, int channels) {
    std::vector<float> scratch(size_t(n) * n * channels);
    for (int face = 0; face < 6; ++face) forward_face(data + size_t(face) * n * n * channels, n, channels, scratch.data());
}

void inverse_cube(float* data, int n, int channels) {
    std::vector<float> scratch(size_t(n) * n * channels);
    for (int face = 0; face < 6; ++face) inverse_face(data + size_t(face) * n * n * channels, n, channels, scratch.data());
}

int support_side(int i, int j, int n) {
    const int m = std::max(i, j);
    if (m <= 1) return n;  // scaling coefficient and the coarsest details
    int level = 1;         // largest power of two ≤ m
    while (level * 2 <= m) level *= 2;
    return n / level;
}

LightingApproximation::LightingApproximation(int resolution) : n_(resolution) {
    check_resolution(resolution);
    coefficients_.resize(size_t(6) * n_ * n_ * 3);
    weights_.resize(size_t(6) * n_ * n_);
    order_.resize(size_t(6) * n_ * n_);
}

void LightingApproximation::approximate(const CubeMap& map, int terms, SparseLighting& out) {
    RSL_CHECK_EQ(map.resolution(), n_);
    RSL_CHECK_GE(terms, 0);
    const int count = map.texel_count();
    for (int k = 0; k < count; ++k) {
        const Color& L = map.radiance(k);
        coefficients_[3 * k] = L.r, coefficients_[3 * k + 1] = L.g, coefficients_[3 * k + 2] = L.b;
    }
    forward_cube(coefficients_.data(), n_, 3);
    const int per_face = n_ * n_;
    for (int k = 0; k < count; ++k) {
        const int rest = k % per_face;
        const int side = support_side(rest % n_, rest / n_, n_);
        const float magnitude = 0.2126f * std::abs(coefficients_[3 * k]) + 0.7152f * std::abs(coefficients_[3 * k + 1]) +
                                0.0722f * std::abs(coefficients_[3 * k + 2]);
        weights_[k] = magnitude * float(side * side);
        order_[k] = k;
    }
    const int kept = std::min(terms, count);
    // Largest first; ties broken by index so the choice is deterministic.
    std::partial_sort(order_.begin(), order_.begin() + kept, order_.end(), [&](int32_t a, int32_t b) {
        return weights_[a] != weights_[b] ? weights_[a] > weights_[b] : a < b;
    });
    out.index.resize(size_t(kept));
    out.value.resize(size_t(kept));
    for (int t = 0; t < kept; ++t) {
        const int k = order_[t];
        out.index[t] = k;
        out.value[t] = Color(coefficients_[3 * k], coefficients_[3 * k + 1], coefficients_[3 * k + 2]);
    }
}

CubeMap reconstruct(const SparseLighting& lighting, int resolution) {
    CubeMap map(resolution);
    std::vector<float> data(size_t(map.texel_count()) * 3, 0.0f);
    for (size_t t = 0; t < lighting.size(); ++t)
        for (int c = 0; c < 3; ++c) data[3 * size_t(lighting.index[t]) + c] = lighting.value[t][c];
    inverse_cube(data.data(), resolution, 3);
    for (int k = 0; k < map.texel_count(); ++k) map.radiance(k) = Color(data[3 * k], data[3 * k + 1], data[3 * k + 2]);
    return map;
}

}  // namespace rsl::haar
