#pragma once
// Rotatable square lights (RSL paper §4.1; docs/design/METHOD.md "Rotatable square lights").
//
// An RSL ⟨c, r, I⟩ is a square of uniform radiance I centred on the unit
// direction c with half-diagonal r. "Square" means: in the fitting chart at c
// (Lambert's azimuthal equal-area projection about c, scaled so that plane area
// equals solid angle, see src/lightfit/square_fit.h) it is a square of edge √2·r,
// so its solid angle is exactly 2r². It is *rotatable*: its turn about c is not
// part of the light, each renderer chooses it (the runtime aligns it with the
// vertex's local frame). Its light integral 2r²·I equals the energy of the
// region it was fitted to, per RGB channel.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "src/core/math.h"

namespace rsl {

struct IrradianceMap;  // src/lightfit/irradiance.h

struct RotatableSquareLight {
    Vec3 center{0, 0, 1};       // unit direction (world space)
    float half_diagonal = 0;    // r; solid angle 2r²
    Color radiance{0};          // I, average radiance over the square
    int texel_count = 0;        // texels of the region it was fitted to
    float fit_error = 0;        // |S′|·E_θ[∫(T − F_θ)²] of the fit, relative to |map energy|²

    float solid_angle() const { return 2.0f * half_diagonal * half_diagonal; }
    // ∫ F dω = 2r²·I, per channel (the region's energy).
    DVec3 light_integral() const { return DVec3(radiance) * double(solid_angle()); }
};

struct RslSet {
    std::vector<RotatableSquareLight> lights;
    int resolution = 0;  // N of the 6×N×N cube map the set was fitted to
    // Region (light index) of every texel of that cube map, in CubeMap::index
    // order; empty when unknown (e.g. after a rotation). For previews and tests.
    std::vector<int> region_of_texel;
    // The exact irradiance over normals of the map (and suns) the set was
    // fitted to, in the set's frame; null when unknown (a set loaded from a
    // file or rotated): renderers then shade the diffuse light with the
    // squares alone (docs/design/RENDERER.md "Exact diffuse light").
    std::shared_ptr<const IrradianceMap> irradiance;

    DVec3 total_energy() const;

    // Rotating the environment by R rotates every center: the set is fitted
    // once. Region labels and the irradiance describe the unrotated map, so
    // they are dropped.
    void rotate(const Mat3& rotation);
};

// JSON (see docs/design/LIGHTFIT.md for the format). Saving is atomic; loading
// validates every field and throws rsl::Error naming the file and the field.
void save_rsl_set(const std::filesystem::path& path, const RslSet& set);
RslSet load_rsl_set(const std::filesystem::path& path);

}  // namespace rsl
