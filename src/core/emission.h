#pragma once
// Emission: radiance a surface gives off itself (MaterialDesc::emissive ×
// emissive_texture at the point's texture coordinates), added to the light it
// reflects. It lights no other surface: a local light does that
// (docs/SCENE_FORMAT.md "materials", docs/design/RENDERER.md "Emission").
// The renderers and the truth add it the same way: per vertex, the emission
// at the vertex's texture coordinates; per pixel, at the pixel's.
#include <string>
#include <vector>

#include "src/core/scene.h"

namespace rsl {

// Whether an emission gives off any light.
inline bool emits(const Color& emissive) { return emissive.r > 0.0f || emissive.g > 0.0f || emissive.b > 0.0f; }
inline bool emits(const MaterialDesc& m) { return emits(m.emissive); }
// Whether its emission varies over a surface (a texture), so that a pixel
// needs its own value rather than its vertices' blend.
inline bool emission_varies(const MaterialDesc& m) { return emits(m) && m.emissive_texture != nullptr; }

// emissive × texture(uv) (Texture::lookup: its sampler's filter); the texture counts as 1 when absent (null).
Color emission_at(const Color& emissive, const Texture* texture, const Vec2& uv);
inline Color emission_at(const MaterialDesc& m, const Vec2& uv) {
    return emission_at(m.emissive, m.emissive_texture.get(), uv);
}
// The emission at each vertex of `mesh` (texture coordinates needed with a
// texture; the caller checks, see emission_fits).
std::vector<Color> vertex_emission(const Color& emissive, const Texture* texture, const TriangleMesh& mesh);
inline std::vector<Color> vertex_emission(const MaterialDesc& m, const TriangleMesh& mesh) {
    return vertex_emission(m.emissive, m.emissive_texture.get(), mesh);
}
// Whether a part can show the material's emission: its mesh has texture
// coordinates when the emission is textured.
bool emission_fits(const MaterialDesc& m, const TriangleMesh& mesh);

// What is wrong with an emission value (finite, ≥ 0, ≤ kMaxEmission per
// channel, src/core/scene_limits.h), as a phrase ("channel G is -1: …"), or empty.
std::string emission_problem(const Color& emissive);
// A value for the `emissive` parameter (an RGB triple or one number for
// all three) checked as above; throws rsl::Error naming `material`.
Color checked_emission(const std::string& material, const std::vector<float>& value);

}  // namespace rsl
