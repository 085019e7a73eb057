#pragma once
// One entry point per demo (demos/<name>_demo.cpp); run_demo dispatches.
#include "demos/demo.h"

namespace rsl::demos {

DemoResult run_robot_demo(const DemoOptions& options);
DemoResult run_kitchen_demo(const DemoOptions& options);
DemoResult run_materials_demo(const DemoOptions& options);
DemoResult run_compare_demo(const DemoOptions& options);
DemoResult run_walker_demo(const DemoOptions& options);

}  // namespace rsl::demos

#include "src/core/scene.h"

namespace rsl::demos {

// Materials: the glossiness sweep. A roughness r in [0, 1] (0: mirror-like)
// mapped onto each model's own parameter (Phong exponent 2/r² − 2, the
// Beckmann-equivalent; Cook-Torrance roughness r; Ward α = r; anisotropic
// Ward α_x = r, α_y = r/4). Throws rsl::Error for a model without one.
void set_glossiness(MaterialDesc& material, float roughness);
// The sweep's roughness at frame f of n: from 0.06 to 0.5.
float sweep_roughness(int frame, int frames);

}  // namespace rsl::demos
