#pragma once
// The per-vertex transport both PRT baselines precompute, sampled on the
// environment's cube-map texels at a fixed view (Ng et al. 2003 fix the view
// for glossy transport; a Lambertian BRDF makes it view-independent):
//
//   f_k(x) = ρ(ω_k, ω_o) · max(0, n·ω_k) · V(x, ω_k)        (RGB, no solid angle)
//
// for every texel k, with ω_k the texel's center direction turned by the
// environment's rotation at precompute time, exactly the directions,
// horizon rules, ray origins and offsets the ground truth uses
// (src/trace/ground_truth.cpp), so that Σ_k L_k f_k Ω_k *is* the ground truth
// and each baseline's error is its own approximation only.
#include <cstdint>
#include <vector>

#include "src/core/envmap.h"
#include "src/trace/ground_truth.h"
#include "src/formats/vertex_colors.h"

namespace rsl {

// Every vertex of every part as one flat index, parts in order.
class VertexLayout {
public:
    explicit VertexLayout(const Scene& scene);
    size_t total() const { return first_.back(); }
    int parts() const { return int(first_.size()) - 1; }
    size_t first(int part) const { return first_[part]; }
    // (part, vertex) of a flat index.
    std::pair<int, int> locate(size_t flat) const;
    // VertexColors of the scene from flat RGB values.
    VertexColors to_colors(const Scene& scene, const std::vector<Color>& flat, const std::string& producer,
                           float time) const;

private:
    std::vector<size_t> first_;  // first flat index of each part, then the total
};

class TransportSampler {
public:
    // `truth` supplies the posed scene, the part BRDFs and the camera; the
    // texel directions are `grid`'s, turned by `environment_rotation`.
    // With `visibility` false no ray is traced and V = 1 (the unshadowed
    // transport, for attributing a renderer's error to lighting or shadows).
    TransportSampler(const GroundTruth& truth, const CubeMap& grid, const Mat3& environment_rotation,
                     bool visibility = true);

    int texel_count() const { return int(directions_.size()); }
    const std::vector<Vec3>& directions() const { return directions_; }

    // Per-thread buffers, so that sample() does not allocate.
    struct Scratch {
        std::vector<Vec3> dirs;
        std::vector<int32_t> texels;
        std::vector<Color> weights;
        std::vector<uint8_t> visible;
    };
    Scratch make_scratch() const;

    // f_k of vertex (part, vertex) into f[0 .. texel_count); returns the
    // number of shadow rays traced.
    uint64_t sample(int part, int vertex, Color* f, Scratch& scratch) const;
    // V_k alone into V[0 .. texel_count): 1 where the texel is above the
    // vertex's shading and geometric horizons and its ray is unoccluded, else
    // 0; independent of the view, for the triple product (V·ρ̃ = f where ρ > 0).
    uint64_t sample_visibility(int part, int vertex, float* V, Scratch& scratch) const;

private:
    const GroundTruth& truth_;
    std::vector<Vec3> directions_;
    bool visibility_ = true;
};

}  // namespace rsl
