#pragma once
// Diagnostic only: visibility factors computed exactly, by rays, in place of
// the fields, so that each approximation of the renderer can be switched off
// against the ground truth (docs/RESULTS.md, "Where the error comes from").
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
//            OthersProduct is the error of the split alone).
// Slow (S² rays per vertex and light); not for frames.
#include <memory>
#include <vector>

#include "src/core/scene.h"
#include "src/rays/posed_scene.h"
#include "src/rays/ray_scene.h"

namespace rsl {

enum class ExactVisibilityMode { All, Self, Others, OthersProduct };

class ExactVisibility {
public:
    ExactVisibility(const Scene& scene, float t, ExactVisibilityMode mode, int samples_per_side = 8);
    ExactVisibilityMode mode() const { return mode_; }

    // Visible fraction of the square (plane center, half-edge) in the shading
    // frame of vertex `vertex` of part `part`; 1 when no grid point is above
    // the horizon.
    float visible_fraction(int part, int vertex, const Vec2& center, float half_edge) const;

private:
    const RayScene& occluders_of(int part) const;
    float fraction(const RayScene& rays, const SurfacePoint& x, const Vec3& origin, const Vec2& center,
                   float half_edge) const;

    ExactVisibilityMode mode_;
    int samples_;
    PosedScene posed_;                                // frames, offsets; the All mode's occluders
    std::vector<std::unique_ptr<RayScene>> per_part_;  // per receiver part: Self / Others: its occluders;
                                                       // OthersProduct: the part alone
};

}  // namespace rsl
