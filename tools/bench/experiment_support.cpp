#include "tools/bench/experiment_support.h"

#include <filesystem>

namespace rsl {

void adapt_scene(Scene& scene, const std::string& environment, int resolution, bool diffuse) {
    if (!environment.empty()) {
        scene.environment.file = std::filesystem::absolute(environment);
        scene.environment.second_file.clear();
    }
    if (resolution > 0) scene.environment.resolution = resolution;
    if (!diffuse) return;
    for (MaterialDesc& m : scene.materials) {
        std::vector<float> albedo{0.5f, 0.5f, 0.5f};
        for (const char* key : {"albedo", "kd"})
            if (auto it = m.params.find(key); it != m.params.end()) albedo = it->second;
        if (albedo.size() == 1) albedo = {albedo[0], albedo[0], albedo[0]};
        m.model = "lambert";
        m.params = {{"albedo", albedo}};
        m.file.clear();
    }
}

}  // namespace rsl
