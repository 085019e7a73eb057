#pragma once
// The materials and compare demos' object, "orb": a sphere inside a tilted
// ring. Small (a few thousand vertices), round enough to show a highlight's
// shape, and it shadows itself (ring on sphere, sphere on ring), so the SVDF
// matters. `rsl assets` writes it as assets/generated/orb.obj.
#include "src/core/mesh.h"

namespace rsl::assets {

// Resting on y = 0 (the sphere touches the floor), centered on the Y axis.
TriangleMesh make_orb();

}  // namespace rsl::assets
