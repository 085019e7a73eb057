// Robot (RSL paper Figure 13): the 12-part walking robot on the ground under
// the sun/sky map, which turns about the vertical axis, seen from a camera
// moving on a path. The sun's sharp shadow on the ground and on the robot
// itself moves with the limbs: the OVDFs of the parts (others' shadows) and
// the SVDFs (self-shadows) are looked up every frame.
#include <fmt/format.h>

#include "demos/demo_runners.h"
#include "demos/demo_support.h"

namespace rsl::demos {

DemoResult run_robot_demo(const DemoOptions& options) {
    return run_scene_sequence(options, "robot", "robot/scene.json", [](const Scene& scene, int lights) {
        return fmt::format("{} vertices, {} square lights, sun/sky turning {:.0f} deg/s", scene.vertex_count(), lights,
                           scene.environment.rotation_degrees_per_second);
    });
}

}  // namespace rsl::demos
