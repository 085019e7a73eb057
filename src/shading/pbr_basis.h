#pragma once
// glTF metallic-roughness varying over a surface (docs/design/BRDF.md
// "Textured roughness and metallic"). gltf_pbr's BRDF is linear in three
// grey lobes:
//
//   ρ(base, m, r) = kd (1 − f0)² · D  +  (1 − f0)/0.96 · S(0.04, r)  +  (f0 − 0.04)/0.96 · S(1, r),
//   kd = base (1 − m),   f0 = mix(0.04, base, m),
//
// D the diffuse lobe at kd = 1, f0 = 0 (the same at every roughness:
// Schlick's Fresnel factors out of it as (1 − f0)²), S(f0, r) the GGX
// specular lobe at α = r², linear in f0. The tables hold D once and
// S(0.04, ·), S(1, ·) at kPbrLevels roughness levels; a point between two
// levels blends their averages linearly. Exact in base colour and metallic.
#include "src/shading/glsl_subset.h"

namespace rsl::shading {

// RSL_GLSL_BEGIN

RSL_CONST int kPbrLevels = 11;  // roughness 0, 0.1, …, 1
RSL_CONST float kPbrDielectricF0 = 0.04f;

// A point's weights on the basis, per colour channel.
struct PbrWeights {
    vec3 diffuse;     // on D
    vec3 dielectric;  // on S(0.04, ·), before the levels' weights
    vec3 metal;       // on S(1, ·), before the levels' weights
    int level;        // j: the lower of the two roughness levels blended
    float upper;      // the weight of level j + 1 (level j has 1 − upper)
};
RSL_SHARED PbrWeights pbr_weights(vec3 base, float metallic, float roughness) {
    PbrWeights w;
    vec3 f0 = mix(vec3(kPbrDielectricF0), base, metallic);
    vec3 one_minus_f0 = vec3(1.0f) - f0;
    w.diffuse = base * (1.0f - metallic) * one_minus_f0 * one_minus_f0;
    w.dielectric = one_minus_f0 * (1.0f / (1.0f - kPbrDielectricF0));
    w.metal = (f0 - vec3(kPbrDielectricF0)) * (1.0f / (1.0f - kPbrDielectricF0));
    float x = clamp(roughness, 0.0f, 1.0f) * float(kPbrLevels - 1);
    w.level = min(int(x), kPbrLevels - 2);
    w.upper = x - float(w.level);
    return w;
}
// The roughness of level j.
RSL_SHARED float pbr_level_roughness(int j) { return float(j) / float(kPbrLevels - 1); }
// The weight of roughness level j in a point's blend.
RSL_SHARED float pbr_level_weight(int level, float upper, int j) {
    return j == level ? 1.0f - upper : (j == level + 1 ? upper : 0.0f);
}

// RSL_GLSL_END

}  // namespace rsl::shading
