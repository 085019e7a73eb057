#include "src/image/error_metrics.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <string_view>

#include "src/core/error.h"
#include "src/core/texture.h"

namespace rsl {

namespace {

DVec3 rgb(const Image& image, int x, int y) {
    const float* p = image.at(x, y);
    return DVec3(p[0], p[1], p[2]);
}

bool covered(const Image& image, int x, int y) { return image.channels < 4 || image.at(x, y)[3] > 0.0f; }

}  // namespace

double relative_l2(const std::vector<Color>& a, const std::vector<Color>& b) {
    RSL_CHECK_EQ(a.size(), b.size());
    ErrorStats stats;
    for (size_t i = 0; i < a.size(); ++i) stats.add(a[i], b[i]);
    return stats.relative_l2();
}

void ErrorStats::add(const Color& a, const Color& b) {
    const DVec3 d = DVec3(a) - DVec3(b);
    const double e2 = glm::dot(d, d), b2 = glm::dot(DVec3(b), DVec3(b));
    diff_squared += e2;
    reference_squared += b2;
    max_error = std::max(max_error, std::sqrt(e2));
    max_reference = std::max(max_reference, std::sqrt(b2));
    ++count;
}

double ErrorStats::relative_l2() const {
    if (reference_squared > 0) return std::sqrt(diff_squared / reference_squared);
    return diff_squared > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}

double ErrorStats::relative_max() const {
    if (max_reference > 0) return max_error / max_reference;
    return max_error > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}

void ErrorStats::merge(const ErrorStats& other) {
    diff_squared += other.diff_squared;
    reference_squared += other.reference_squared;
    max_error = std::max(max_error, other.max_error);
    max_reference = std::max(max_reference, other.max_reference);
    count += other.count;
}

bool is_receiver(const std::string& name, const std::string& receiver) {
    // The name without a trailing copy number: digits after '.', '_' or '-'.
    size_t end = name.size();
    while (end > 0 && std::isdigit(static_cast<unsigned char>(name[end - 1]))) --end;
    const bool numbered = end < name.size() && end > 0 && (name[end - 1] == '.' || name[end - 1] == '_' || name[end - 1] == '-');
    const std::string_view base = numbered ? std::string_view(name).substr(0, end - 1) : std::string_view(name);
    return base.size() == receiver.size() &&
           std::equal(base.begin(), base.end(), receiver.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

ObjectErrorReport object_errors(const VertexErrorReport& report, const std::vector<std::string>& receivers) {
    ObjectErrorReport result;
    for (size_t p = 0; p < report.parts.size(); ++p) {
        if (std::any_of(receivers.begin(), receivers.end(),
                        [&](const std::string& r) { return is_receiver(report.part_names[p], r) || report.part_names[p] == r; }))
            continue;
        result.objects.merge(report.parts[p]);
        ++result.object_parts;
        if (result.worst_part.empty() || report.parts[p].relative_l2() > result.worst) {
            result.worst = report.parts[p].relative_l2();
            result.worst_part = report.part_names[p];
        }
    }
    return result;
}

VertexErrorReport compare_vertex_colors(const VertexColors& a, const VertexColors& b) {
    RSL_CHECK_EQ(a.parts.size(), b.parts.size());
    VertexErrorReport report;
    report.part_names = b.part_names;
    report.parts.resize(b.parts.size());
    for (size_t p = 0; p < b.parts.size(); ++p) {
        RSL_CHECK_EQ(a.parts[p].size(), b.parts[p].size());
        // A textured part is compared at unit texture: diffuse + specular.
        const bool layers = a.layered(p) && b.layered(p);
        for (size_t v = 0; v < b.parts[p].size(); ++v) {
            const Color x = layers ? a.parts[p][v] + a.specular[p][v] : a.parts[p][v];
            const Color y = layers ? b.parts[p][v] + b.specular[p][v] : b.parts[p][v];
            report.parts[p].add(x, y);
            report.total.add(x, y);
        }
    }
    return report;
}

ImageErrorReport compare_images(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw_error("images are not comparable: {}×{} vs {}×{} pixels", a.width, a.height, b.width, b.height);
    if (a.channels < 3 || b.channels < 3) throw_error("images need RGB channels");
    ImageErrorReport report;
    report.total = size_t(a.width) * a.height;
    // Only the reference's coverage decides (see ImageErrorReport).
    auto in = [&](int x, int y) { return covered(b, x, y); };
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!in(x, y)) continue;
            ++report.covered;
            report.pixels.add(Color(rgb(a, x, y)), Color(rgb(b, x, y)));
            // Gradients by forward differences, where both ends are covered
            // (a silhouette against the background is not a shading gradient).
            for (const auto [dx, dy] : {std::array{1, 0}, std::array{0, 1}}) {
                const int nx = x + dx, ny = y + dy;
                if (nx >= a.width || ny >= a.height || !in(nx, ny)) continue;
                report.gradient.add(Color(rgb(a, nx, ny) - rgb(a, x, y)), Color(rgb(b, nx, ny) - rgb(b, x, y)));
            }
        }
    return report;
}

Color false_color(float x) {
    // Piecewise-linear through sRGB stops, converted to linear.
    static constexpr std::array<std::array<float, 3>, 5> stops = {
        {{0.05f, 0.05f, 0.35f}, {0.0f, 0.45f, 0.9f}, {0.1f, 0.85f, 0.75f}, {0.98f, 0.9f, 0.2f}, {0.85f, 0.1f, 0.05f}}};
    const float t = std::clamp(std::isfinite(x) ? x : 1.0f, 0.0f, 1.0f) * float(stops.size() - 1);
    const int i = std::min(int(t), int(stops.size()) - 2);
    const float f = t - float(i);
    Color c;
    for (int k = 0; k < 3; ++k) {
        c[k] = srgb_to_linear(stops[i][k] * (1 - f) + stops[i + 1][k] * f);
    }
    return c;
}

Image error_image(const Image& a, const Image& b, float scale) {
    if (a.width != b.width || a.height != b.height)
        throw_error("images are not comparable: {}×{} vs {}×{} pixels", a.width, a.height, b.width, b.height);
    Image out(a.width, a.height, 3);
    if (scale <= 0) {
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) scale = std::max(scale, float(glm::length(rgb(a, x, y) - rgb(b, x, y))));
        if (scale <= 0) scale = 1;
    }
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            if (covered(a, x, y) || covered(b, x, y))
                out.set_rgb(x, y, false_color(float(glm::length(rgb(a, x, y) - rgb(b, x, y))) / scale));
    return out;
}

}  // namespace rsl
