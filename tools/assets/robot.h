#pragma once
// The robot: 12 rigid parts built from smooth closed solids, about 60k
// vertices in all, walking in place in a 2-second loop; and the finely
// tessellated ground it walks on (a separate part/file so other scenes reuse it).
#include "tools/assets/model.h"

namespace rsl::assets {

inline constexpr float kRobotWalkSeconds = 2.0f;  // one full stride: left step + right step

// Nodes (parent first): torso (root, carries the bob and sway), head, upper
// arms, forearms, hands, thighs, shins (with the feet). The robot faces +Z,
// its left is +X, the ground is y = 0.
GeneratedModel make_robot();

// 8 m × 8 m sheet at y = 0 with 160 × 160 cells (5 cm), normal +Y.
TriangleMesh make_ground();

}  // namespace rsl::assets
