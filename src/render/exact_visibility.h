#pragma once
// Diagnostic only: visibility factors computed exactly, by rays, in place of
// the fields, so that each approximation of the renderer can be switched off
// against the ground truth (docs/journal/results-history.md, "Where the error comes from").
//
// The exact visible fraction of a square light at a vertex is the share of an
// S×S grid of points of the square (in the vertex's equal-area plane, the
// square's own parameterization) whose directions above the horizon reach the
// sky, rays leaving the vertex exactly as the ground truth's do
// (PosedScene::vertex, RayOffset). Which geometry occludes is the mode:
//   All    — every part: replaces SVDF × Π OVDF (tests the fields as a whole
//            and the split of visibility into self × others);
//   Self   — the vertex's own part: replaces the SVDF;
//   Others — every other part at once: replaces Π OVDF (tests the OVDF's
//            sampling, interpolation, compression and outer shell, and the
//            split of the others' shadow into a product over parts);
//   OthersProduct — Π over the other parts j of each one's exact average:
//            the renderer's product split with exact factors (so Others vs
//            OthersProduct is the error of the split alone);
//   SelfTimesOthers — the vertex's own part's exact average × the other
//            parts' (at once): replaces SVDF × Π OVDF with both factors
//            exact but averaged apart (so All vs SelfTimesOthers is the
//            error of splitting self from others alone).
// S² rays per vertex and light, in Embree packets from the vertex. With
// `jitter` each grid cell's point is placed at random in its cell
// (stratified sampling, seeded by the part, the vertex and the light, so a
// frame is reproducible and the GL renderer's rays are the same:
// src/shading/ray_samples.h): the ray-traced many-light baseline (docs/BASELINES.md),
// where S = 1, 2, 4 are its settings and noise is its error. Without jitter
// the points are the cell centres: the deterministic diagnostic.
#include <memory>
#include <vector>

#include "src/core/scene.h"
#include "src/rays/posed_scene.h"
#include "src/rays/ray_scene.h"

namespace rsl {

enum class ExactVisibilityMode { All, Self, Others, OthersProduct, SelfTimesOthers };

class ExactVisibility {
public:
    static constexpr int kMaxSamplesPerSide = 16;
    // Throws rsl::Error when samples_per_side is outside [1, kMaxSamplesPerSide].
    ExactVisibility(const Scene& scene, float t, ExactVisibilityMode mode, int samples_per_side = 8,
                    bool jitter = false);
    ExactVisibilityMode mode() const { return mode_; }
    int samples_per_side() const { return samples_; }

    // Visible fraction of light `light`'s square (plane center, half-edge) in
    // the shading frame of vertex `vertex` of part `part`; 1 when no grid
    // point is above the horizon. The light's index only seeds the jitter.
    // `rays`, when given, is increased by the rays traced.
    float visible_fraction(int part, int vertex, int light, const Vec2& center, float half_edge,
                           size_t* rays = nullptr) const;
    // The same for m squares of light `light` at once (the renderer's block):
    // query i is vertex first_vertex + offset[i] of `part`, square
    // (center_x[i], center_y[i]) with half-edge half_edge[i]; out[i] its
    // visible fraction, 0 where skip[i] (skip may be null). The rays of all
    // queries go to Embree together, in packets of neighbouring vertices'
    // rays (coherent: one light), which is several times faster than one
    // query at a time when S is small. Thread-safe; no allocation once warm.
    void visible_fraction_batch(int part, int first_vertex, int light, const int* offset, const float* center_x,
                                const float* center_y, const float* half_edge, const bool* skip, int m, float* out,
                                size_t* rays = nullptr) const;

private:
    const RayScene& occluders_of(int part) const;
    shading::uvec2 seed(int part, int vertex, int light) const;
    // The directions of the square's grid points that leave the surface
    // (written to dirs, at most S² of them, returned); `counted` is the
    // number of grid points above the shading horizon.
    int square_directions(const SurfacePoint& x, const Vec2& center, float half_edge, shading::uvec2 seed,
                          Vec3* dirs, int& counted) const;
    float fraction(const RayScene& rays, const SurfacePoint& x, const Vec3& origin, const Vec2& center,
                   float half_edge, shading::uvec2 seed, size_t* traced) const;

    ExactVisibilityMode mode_;
    int samples_;
    bool jitter_;
    uint64_t id_;  // tells this object's per-thread vertex cache from another's
    PosedScene posed_;                                // frames, offsets; the All mode's occluders
    std::vector<std::unique_ptr<RayScene>> per_part_;  // per receiver part: Self / Others: its occluders;
                                                       // OthersProduct: the part alone; SelfTimesOthers:
                                                       // two per part, [2p] itself and [2p + 1] the others
};

}  // namespace rsl
