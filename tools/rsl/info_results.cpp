// `rsl info` for what the program itself writes besides fields: per-vertex
// results (.rslv, from `rsl render` / `rsl truth`) and light sets (.json
// from `rsl fit`, told apart from scene files by their "format" key).
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "src/lightfit/square_light.h"
#include "tools/rsl/info.h"
#include "src/formats/json_file.h"
#include "src/formats/vertex_colors.h"

namespace rsl::cli {

bool is_light_set_file(const std::filesystem::path& path) {
    if (lowercase_extension(path) != ".json") return false;
    try {
        const nlohmann::json root = read_json_file(path);
        return root.is_object() && root.value("format", "") == "rsl-lights";
    } catch (const std::exception&) {
        return false;  // the scene handler reports what is wrong with it
    }
}

namespace {

void print_vertex_colors(const std::filesystem::path& path) {
    const VertexColors colors = read_vertex_colors(path);  // checks magic, version, size, checksum, finiteness
    fmt::print("{}: per-vertex colours (rsl .rslv, version {})\n", path.string(), kVertexColorsVersion);
    fmt::print("  scene:             {}\n", colors.scene_name);
    fmt::print("  producer:          {}\n", colors.producer);
    fmt::print("  time:              {} s\n", colors.time);
    fmt::print("  parts:             {}\n", colors.parts.size());
    fmt::print("  vertices:          {}\n", colors.vertex_count());
    for (size_t p = 0; p < colors.parts.size(); ++p) {
        double sum = 0, peak = 0;
        for (const Color& c : colors.parts[p]) {
            const double y = luminance(c);
            sum += y;
            peak = std::max(peak, y);
        }
        const size_t n = colors.parts[p].size();
        fmt::print("    {:<16} {:>8} vertices, luminance mean {:.4g}, max {:.4g}\n", colors.part_names[p], n,
                   n ? sum / double(n) : 0.0, peak);
    }
}

void print_light_set(const std::filesystem::path& path) {
    const RslSet set = load_rsl_set(path);  // checks format, version and every light
    DVec3 energy(0);
    for (const RotatableSquareLight& light : set.lights) energy += light.light_integral();
    fmt::print("{}: rotatable square lights (rsl-lights)\n", path.string());
    fmt::print("  lights:            {}\n", set.lights.size());
    fmt::print("  fitted on:         6 x {} x {} cube map{}\n", set.resolution, set.resolution,
               set.region_of_texel.empty() ? "" : " (with its regions)");
    fmt::print("  energy (Σ 2r²·I):  RGB ({:.6g}, {:.6g}, {:.6g})\n", energy.x, energy.y, energy.z);
    const auto brightest = std::max_element(set.lights.begin(), set.lights.end(), [](const auto& a, const auto& b) {
        return luminance(Color(a.light_integral())) < luminance(Color(b.light_integral()));
    });
    if (brightest != set.lights.end())
        fmt::print("  brightest light:   center ({:.4g}, {:.4g}, {:.4g}), half-diagonal {:.4g}, radiance ({:.4g}, {:.4g}, "
                   "{:.4g})\n",
                   brightest->center.x, brightest->center.y, brightest->center.z, brightest->half_diagonal,
                   brightest->radiance.x, brightest->radiance.y, brightest->radiance.z);
}

RegisterInfoHandler vertex_colors_info({"vertex colours", [](const auto& p) { return lowercase_extension(p) == ".rslv"; },
                                        print_vertex_colors});
RegisterInfoHandler light_set_info({"light set", is_light_set_file, print_light_set});

}  // namespace
}  // namespace rsl::cli
