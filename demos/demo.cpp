#include "demos/demo.h"

#include <algorithm>

#include <fmt/format.h>

#include "demos/demo_runners.h"
#include "src/core/error.h"

namespace rsl::demos {

const std::vector<DemoInfo>& demo_list() {
    static const std::vector<DemoInfo> demos{
        {"robot", "12-part walking robot, rotating sun/sky, camera path (paper Fig. 13)", "robot/scene.json"},
        {"kitchen", "5 parts, two environment maps cross-faded, a moving local light (Fig. 16)", "kitchen/scene.json"},
        {"materials", "one object in 4 BRDFs, glossiness sweep rebuilding the tables (Fig. 15)", "materials/scene.json"},
        {"compare", "ground truth vs RSL with 10/30/100 lights, error images (Figs. 9, 10)", "compare/scene.json"},
        {"walker", "a skinned, textured character walking round rigid parts, turning sun/sky", "walker/scene.json"},
    };
    return demos;
}

DemoResult run_demo(const std::string& name, const DemoOptions& options) {
    if (name == "robot") return run_robot_demo(options);
    if (name == "kitchen") return run_kitchen_demo(options);
    if (name == "materials") return run_materials_demo(options);
    if (name == "compare") return run_compare_demo(options);
    if (name == "walker") return run_walker_demo(options);
    std::string names;
    for (const DemoInfo& demo : demo_list()) names += (names.empty() ? "" : ", ") + demo.name;
    throw_error("unknown demo '{}' (demos: {})", name, names);
}

std::vector<std::string> timing_summary(const DemoResult& result) {
    std::vector<std::string> lines;
    if (result.timings.empty()) return lines;
    auto stat = [&](const char* what, double FrameTiming::*field) {
        double sum = 0, lo = 1e30, hi = 0;
        for (const FrameTiming& t : result.timings) {
            sum += t.*field;
            lo = std::min(lo, t.*field), hi = std::max(hi, t.*field);
        }
        if (hi == 0) return;
        lines.push_back(fmt::format("{:<8} mean {:8.1f} ms  min {:8.1f} ms  max {:8.1f} ms", what,
                                    1e3 * sum / double(result.timings.size()), 1e3 * lo, 1e3 * hi));
    };
    stat("update", &FrameTiming::update_seconds);
    stat("shading", &FrameTiming::shade_seconds);
    stat("image", &FrameTiming::image_seconds);
    return lines;
}

}  // namespace rsl::demos
