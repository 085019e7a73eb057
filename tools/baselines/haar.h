#pragma once
// Haar wavelets on the cube map, for the wavelet PRT baseline (Ng,
// Ramamoorthi, Hanrahan 2003).
//
// Each N×N face (N a power of 2) is transformed with the *non-standard* 2D
// Haar decomposition: at every level each 2×2 block (a b / c d) becomes its
// orthonormal average and three details,
//
//   s = (a + b + c + d)/2,  h = (a − b + c − d)/2,  v = (a + b − c − d)/2,  g = (a − b − c + d)/2,
//
// the averages of a level of side S go to the top-left (S/2)² block and the
// details to the three others, and the next level works on the averages. The
// transform is orthonormal, so Σ_k L_k g_k = Σ_j (WL)_j (Wg)_j exactly: the
// lighting and the transport (which carries the texels' solid angles) are
// transformed alike and the rendering sum becomes a sparse dot product.
//
// Layout: values are interleaved channels in CubeMap texel order,
// data[(face·N² + j·N + i)·channels + c]; coefficient positions use the same
// indices (i, j within the face).
#include <cstdint>
#include <vector>

#include "src/core/envmap.h"
#include "src/core/math.h"

namespace rsl::haar {

bool is_power_of_two(int n);

// One face, in place: `data` is N×N×channels (row j, column i).
void forward_face(float* data, int n, int channels, float* scratch);
void inverse_face(float* data, int n, int channels, float* scratch);
// All six faces of a 6×N×N map, in place.
void forward_cube(float* data, int n, int channels);
void inverse_cube(float* data, int n, int channels);

// Side, in texels, of the square support of the coefficient at (i, j) of a
// face of side N: the scaling coefficient (0, 0) and the coarsest details
// cover the face; a detail at max(i, j) ∈ [2^s, 2^(s+1)) covers N / 2^s.
int support_side(int i, int j, int n);

// Ng 2003's nonlinear approximation of the lighting: the `terms` wavelet
// coefficients with the largest area-weighted magnitude, |c| × (support area
// in texels), where |c| is the luminance-weighted sum of the RGB magnitudes.
struct SparseLighting {
    std::vector<int32_t> index;  // cube texel index of each kept coefficient
    std::vector<Color> value;    // its RGB coefficient
    size_t size() const { return index.size(); }
};

class LightingApproximation {
public:
    explicit LightingApproximation(int resolution);
    // Transforms `map` (resolution N) and keeps the `terms` largest. No
    // allocation after the first call.
    void approximate(const CubeMap& map, int terms, SparseLighting& out);
    // The full transform of the last map (RGB interleaved, 6N² × 3).
    const std::vector<float>& coefficients() const { return coefficients_; }

private:
    int n_;
    std::vector<float> coefficients_;
    std::vector<float> weights_;
    std::vector<int32_t> order_;
};

// The map that a sparse lighting represents (inverse transform), for tests
// and previews.
CubeMap reconstruct(const SparseLighting& lighting, int resolution);

}  // namespace rsl::haar
