#pragma once
// The glTF materials showcase (assets/generated/pbr.glb, assets/scenes/pbr.json,
// the README gallery): a ground with a tiled base colour texture and balls
// and a box of different metallic/roughness, every material a glTF
// metallic-roughness material (docs/SCENE_FORMAT.md, "glTF materials").
#include <memory>

#include "tools/assets/model.h"

namespace rsl::assets {

// A glTF metallic-roughness material (model gltf_pbr) as the loader makes one.
MaterialDesc gltf_pbr_material(const std::string& name, Color base, float metallic, float roughness);
// Linear-RGB tiles with grout, `tiles` per side, `texels` per tile.
std::shared_ptr<Texture> make_tile_texture(int tiles, int texels);
// The scene: its materials (gltf_pbr, the ground's textured) on the parts.
GeneratedModel make_pbr_showcase();

}  // namespace rsl::assets
