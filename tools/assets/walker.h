#pragma once
// The project's skinned and textured character (issue 58's demo,
// assets/scenes/walker.json): a figure of capsules on an eight-joint
// skeleton (hips, spine, thighs, shins, arms) walking a circle in a loop,
// its cloth, skin and metal belt from a base colour texture and a
// metallic-roughness texture (docs/DEMOS.md).
#include <memory>

#include "tools/assets/model.h"

namespace rsl::assets {

struct WalkerOptions {
    std::string name = "walker";
    float period = 4;            // seconds per lap of the circle; the animation loops
    int steps_per_lap = 4;       // gait cycles (a step of each leg) per lap
    float circle_radius = 1.0f;  // the hips walk this circle about the origin, counter-clockwise from above
    float spacing = 0.025f;      // vertex spacing of the capsules
};

// The walker alone: its joint nodes ("<name>_hips" the root), one
// GeneratedSkin with material 0 (walker_material()).
GeneratedModel make_walker(const WalkerOptions& options = {});

// Its gltf_pbr material: factors 1, the two textures below.
MaterialDesc walker_material();
// 64×64 atlas, linear RGB (written sRGB): denim legs (v < 0.25), skin arms
// (0.25–0.5), the torso's striped shirt, belt and head (0.5–1).
std::shared_ptr<Texture> walker_base_color_texture();
// The same atlas, linear data: G = roughness (denim 0.9, skin 0.5, shirt
// 0.65, belt 0.3), B = metallic (the belt's buckle band 1, else 0).
std::shared_ptr<Texture> walker_metallic_roughness_texture();

}  // namespace rsl::assets
