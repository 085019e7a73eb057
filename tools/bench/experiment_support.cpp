#include "tools/bench/experiment_support.h"

#include <filesystem>

#include "src/core/atomic_file.h"

namespace rsl {

void adapt_scene(Scene& scene, const std::string& environment, int resolution, bool diffuse) {
    if (!environment.empty()) {
        scene.environment.file = std::filesystem::absolute(environment);
        scene.environment.second_file.clear();
        scene.input_files.push_back(scene.environment.file);
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

void check_experiment_outputs(const Scene& scene, const std::filesystem::path& folder,
                              const std::vector<std::string>& image_stems, const std::vector<std::string>& files) {
    std::vector<std::filesystem::path> outputs;
    for (const std::string& stem : image_stems) {
        outputs.push_back(folder / (stem + ".exr"));
        outputs.push_back(folder / (stem + ".png"));
    }
    for (const std::string& file : files) outputs.push_back(folder / file);
    check_outputs_apart(outputs, scene.input_files);
}

}  // namespace rsl
