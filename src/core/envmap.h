#pragma once
// Environment maps. Everything downstream works on a cube map of 6×N×N texels
// with exact per-texel solid angles.
//
// World convention (docs/design/CONVENTIONS.md, pinned by tests/core/envmap_test.cpp):
// right-handed, +Y up. A latitude-longitude image has row 0 at the top (+Y)
// and its columns span longitude φ ∈ [0, 2π) left to right. In continuous
// image coordinates u, v ∈ [0, 1] (pixel (x, y) of a W×H map has its center at
// u = (x + ½)/W, v = (y + ½)/H):
//
//   θ = π v (polar angle from +Y),  φ = 2π u,
//   d = (sinθ sinφ, cosθ, −sinθ cosφ)
//
// so u = 0 (the left edge) is −Z, u = ¼ is +X, u = ½ (the center) is +Z and
// u = ¾ is −X: OpenEXR's lat-long convention, the image seen from inside the
// sphere. latlong_direction() implements it, latlong_coords() inverts it.
//
// Cube faces are in OpenGL order +X, −X, +Y, −Y, +Z, −Z with OpenGL's (s, t)
// orientation; texel (i, j) of face f covers s ∈ [−1 + 2i/N, −1 + 2(i+1)/N],
// t likewise for j. Face f at (s, t) is the direction
//   +X: (1, −t, −s)  −X: (−1, −t, s)  +Y: (s, 1, t)
//   −Y: (s, −1, −t)  +Z: (s, −t, 1)   −Z: (−s, −t, −1)      (normalized).
#include <array>
#include <filesystem>
#include <vector>

#include "src/core/image.h"
#include "src/core/math.h"

namespace rsl {

Vec3 latlong_direction(float u, float v);  // u, v in [0, 1] image coordinates
Vec2 latlong_coords(const Vec3& dir);      // inverse, u in [0, 1), v in [0, 1]

struct CubeTexel {
    int face = 0, i = 0, j = 0;
};

class CubeMap {
public:
    CubeMap() = default;
    explicit CubeMap(int n);  // black map

    int resolution() const { return n_; }
    int texel_count() const { return 6 * n_ * n_; }
    int index(int face, int i, int j) const { return (face * n_ + j) * n_ + i; }
    CubeTexel texel(int index) const;

    // Direction through face coordinates (s, t) ∈ [−1, 1]² of a face (not normalized → normalized).
    static Vec3 face_direction(int face, float s, float t);
    // Its inverse: the face `dir` points into and its coordinates (s, t) ∈ [−1, 1]²;
    // a zero or NaN direction gives face 0 at (0, 0).
    static int face_coordinates(const Vec3& dir, float& s, float& t);
    Vec3 texel_direction(int index) const;  // unit direction through the texel center
    CubeTexel texel_of(const Vec3& dir) const;
    int index_of(const Vec3& dir) const;

    // Exact solid angle of a texel (sum over the map is 4π to float precision).
    float solid_angle(int index) const { return solid_angle_[index]; }
    const std::vector<float>& solid_angles() const { return solid_angle_; }

    Color& radiance(int index) { return radiance_[index]; }
    const Color& radiance(int index) const { return radiance_[index]; }
    const std::vector<Color>& radiances() const { return radiance_; }
    std::vector<Color>& radiances() { return radiance_; }

    // Nearest-texel radiance in a direction.
    Color lookup(const Vec3& dir) const { return radiance_[index_of(dir)]; }

    // ∫ L dω = Σ L_k Ω_k, per channel, accumulated in double.
    DVec3 energy() const;

    // Indices of the 4 edge-adjacent texels, across face borders too, in the
    // order (i − 1, i + 1, j − 1, j + 1) as seen from this texel's face. Always 4
    // distinct texels, and adjacency is symmetric.
    std::array<int, 4> neighbors(int index) const;

private:
    int n_ = 0;
    std::vector<Color> radiance_;
    std::vector<float> solid_angle_;
};

// Exact solid angle of the face rectangle [s0, s1] × [t0, t1] (unit cube face at distance 1).
double cube_face_solid_angle(double s0, double t0, double s1, double t1);

// Resamples a lat-long image (any size) into a cube map of 6×n×n texels.
// Every resampling below applies estimated overlap areas between source and
// target cells (point-sampled from both sides, then balanced by iterative
// proportional fitting): each source cell, however small and bright, delivers
// its energy exactly (to float precision), and a constant map stays constant
// within 1% (0.5% typical at N = 128). Fitted weights are cached per geometry.
CubeMap cube_from_latlong(const Image& latlong, int n);
// A cube map stored as an image in OpenEXR's vertical-strip layout (width w, height 6w).
CubeMap cube_from_strip(const Image& strip, int n);
// The largest cube map N (6×N×N texels) rsl fits or integrates: the light
// fit holds about 700 bytes a texel (1 GB at 512), and 4096 would need 70 GB.
// Scene files, `rsl fit`, `rsl truth`, `rsl baselines` and the API share it.
inline constexpr int kMaxCubeResolution = 512;


// Energy of a lat-long image as the integral it represents (per-pixel solid angles).
DVec3 latlong_energy(const Image& latlong);

// Rotated environment: L'(d) = L(R⁻¹ d), i.e. content at direction d moves to R d.
CubeMap rotate(const CubeMap& map, const Mat3& rotation);

// (1 − w)·a + w·b texel by texel (the scene format's environment blend);
// the maps must have one resolution.
CubeMap blend_environments(const CubeMap& a, const CubeMap& b, float w);

// Lat-long image of a cube map (for previews and for writing environments as EXR).
Image cube_to_latlong(const CubeMap& map, int width);

// Forgets the cached resampling weights (benchmarks time the cold path with it).
void clear_resampling_cache();

}  // namespace rsl
