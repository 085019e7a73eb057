#include "tools/assets/pbr_scene.h"

#include "tools/assets/primitives.h"

namespace rsl::assets {
MaterialDesc gltf_pbr_material(const std::string& name, Color base, float metallic, float roughness) {
    MaterialDesc m;
    m.name = name;
    m.model = "gltf_pbr";
    m.params = {{"base_color", {base.r, base.g, base.b}}, {"metallic", {metallic}}, {"roughness", {roughness}}};
    return m;
}

std::shared_ptr<Texture> make_tile_texture(int tiles, int texels) {
    auto texture = std::make_shared<Texture>();
    texture->name = "tiles.png";
    const int n = tiles * texels;
    texture->image = Image(n, n, 3);
    // Terracotta and slate tiles in a checker, light grout one texel wide.
    const Color terracotta(0.62f, 0.22f, 0.09f), slate(0.16f, 0.24f, 0.36f), grout(0.75f, 0.72f, 0.66f);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const bool line = x % texels == 0 || y % texels == 0;
            const bool odd = (x / texels + y / texels) % 2 == 1;
            texture->image.set_rgb(x, y, line ? grout : odd ? terracotta : slate);
        }
    return texture;
}

GeneratedModel make_pbr_showcase() {
    GeneratedModel model;
    Scene& scene = model.scene;
    MaterialDesc tiles = gltf_pbr_material("tiles", Color(1.0f), 0.0f, 0.6f);
    tiles.base_color_texture = make_tile_texture(8, 8);
    scene.materials = {tiles,
                       gltf_pbr_material("gold", Color(1.0f, 0.78f, 0.34f), 1.0f, 0.3f),
                       gltf_pbr_material("copper", Color(0.95f, 0.64f, 0.54f), 1.0f, 0.6f),
                       gltf_pbr_material("red_plastic", Color(0.7f, 0.08f, 0.06f), 0.0f, 0.25f),
                       gltf_pbr_material("white_ceramic", Color(0.85f), 0.0f, 0.12f)};
    // 3 m × 3 m of ground, the tiles repeated twice over it (wrap: repeat).
    TriangleMesh ground = grid_plane(3.0f, 3.0f, 48, 48);
    for (const Vec3& p : ground.positions) ground.texcoords.emplace_back((p.x / 3.0f + 0.5f) * 2, (p.z / 3.0f + 0.5f) * 2);
    struct Ball { const char* name; Vec3 at; float radius; int material; };
    const Ball balls[] = {{"gold", Vec3(-0.75f, 0.3f, 0.2f), 0.3f, 1},
                          {"copper", Vec3(0.0f, 0.3f, -0.3f), 0.3f, 2},
                          {"red_plastic", Vec3(0.75f, 0.3f, 0.2f), 0.3f, 3}};
    model.add_node("ground", -1, Vec3(0), ground);
    scene.parts.back().material = 0;
    for (const Ball& b : balls) {
        model.add_node(b.name, -1, b.at, sphere(b.radius, 0.035f));
        scene.parts.back().material = b.material;
    }
    model.add_node("white_ceramic", -1, Vec3(0.0f, 0.18f, 0.6f), rounded_box(Vec3(0.2f, 0.18f, 0.2f), 0.05f, 0.03f));
    scene.parts.back().material = 4;
    for (Part& part : scene.parts) validate_and_complete(part.mesh, "pbr.glb");  // tangents, as the loader's
    return model;
}

}  // namespace rsl::assets
