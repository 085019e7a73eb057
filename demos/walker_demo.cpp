// Walker: the project's skinned, textured character (tools/assets/walker.h)
// walks a circle round a steel orb beside a glazed teapot under the turning
// sun/sky map. Its skin is split into eight rigid segments whose fields move
// with their joints (docs/design/SKINNING.md); its cloth, skin and metal belt
// come from a base colour and a metallic-roughness texture
// (docs/design/BRDF.md "Textured roughness and metallic").
#include <fmt/format.h>

#include "demos/demo_runners.h"
#include "demos/demo_support.h"

namespace rsl::demos {

DemoResult run_walker_demo(const DemoOptions& options) {
    return run_scene_sequence(options, "walker", "walker/scene.json", [](const Scene& scene, int lights) {
        return fmt::format("{} vertices ({} skin segments), {} square lights, sun/sky turning {:.0f} deg/s",
                           scene.vertex_count(), scene.skins.empty() ? 0 : scene.skins[0].joints.size(), lights,
                           scene.environment.rotation_degrees_per_second);
    });
}

}  // namespace rsl::demos
