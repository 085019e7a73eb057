#pragma once
// Helpers of the GL tests: one headless context per test process, scenes with
// real (small) baked fields, and the CPU-vs-GL comparison.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "src/gl/headless_context.h"
#include "src/render/cpu_renderer.h"
#include "src/formats/vertex_colors.h"
#include "tests/render/render_test_scenes.h"

namespace rsl::test {

inline gl::HeadlessContext& gl_context() {
    static gl::HeadlessContext context;
    context.make_current();
    return context;
}

struct ColorDifference {
    double relative_l2 = 0;       // ‖gl − cpu‖₂ / ‖cpu‖₂ over all vertices and channels
    double max_relative = 0;      // max over vertices of |gl − cpu| / max(|cpu|, floor)
    size_t vertices = 0, over_tolerance = 0;
    double mean_luminance = 0;
};

// Per vertex and channel, |gl − cpu| is compared with tolerance·max(|cpu|,
// floor), where floor = 1e-2 × the mean |cpu| over the scene: values far below
// the scene's level (deep shadow, grazing views) are compared absolutely.
// `specular`: the textured parts' specular layers (VertexColors::specular)
// instead of `parts`; a part layered in one and not the other counts all its
// vertices as over the tolerance.
inline ColorDifference compare_colors(const VertexColors& gl, const VertexColors& cpu, double tolerance,
                                      bool specular = false) {
    ColorDifference d;
    const auto& expected = specular ? cpu.specular : cpu.parts;
    const auto& actual = specular ? gl.specular : gl.parts;
    double sum = 0, error2 = 0, norm2 = 0;
    size_t values = 0;
    for (const auto& part : expected)
        for (const Color& c : part) sum += std::abs(c.r) + std::abs(c.g) + std::abs(c.b), values += 3;
    const double floor = 1e-2 * sum / std::max<size_t>(values, 1);
    d.mean_luminance = sum / std::max<size_t>(values, 1);
    for (size_t p = 0; p < expected.size(); ++p) {
        const size_t vertices = std::max(expected[p].size(), p < actual.size() ? actual[p].size() : 0);
        if (p >= actual.size() || actual[p].size() != expected[p].size()) {
            d.vertices += vertices, d.over_tolerance += vertices;
            d.max_relative = d.relative_l2 = INFINITY;
            continue;
        }
        for (size_t v = 0; v < expected[p].size(); ++v) {
            double worst = 0;
            for (int c = 0; c < 3; ++c) {
                const double a = actual[p][v][c], b = expected[p][v][c];
                error2 += (a - b) * (a - b), norm2 += b * b;
                worst = std::max(worst, std::abs(a - b) / std::max(std::abs(b), floor));
            }
            d.max_relative = std::max(d.max_relative, worst);
            d.over_tolerance += worst > tolerance ? 1 : 0;
            ++d.vertices;
        }
    }
    if (std::isfinite(d.relative_l2)) d.relative_l2 = std::sqrt(error2 / std::max(norm2, 1e-30));
    return d;
}

}  // namespace rsl::test
