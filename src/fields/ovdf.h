#pragma once
// Occluder visibility distance field (RSL paper §4.3.2, §5.1; shadow fields,
// Zhou et al. 2005): around a rigid part, sample points on concentric shells,
// each shell sampled like a cube map; at every sample point q the VDT of the
// part on the hemisphere whose pole points from q to the part's center.
// Compressed by PCA per segment (each cube face split 2×2: 24 segments per
// shell).
//
// Sample frames: z = (center − q)/|center − q|; x = the face's s axis made
// orthogonal to z. Within a face this is smooth (z stays within 55° of the
// face normal, which is orthogonal to s), so neighbouring samples' frames
// agree up to the angle between them; it jumps at face edges, where blending
// reads each sample in its own frame anyway (docs/design/FIELDS.md).
//
// Zoomed tables: seen from a sample at distance d > R, the part lies within
// the cone of half-angle asin(R/d) around the pole, the disk |p| < e(d) =
// √2·sin(½·asin(R/d)) of the equal-area plane. Each shell's tables cover the
// plane scaled by its zoom k = max(1, kOvdfZoomEdge / e) (table point k·p),
// so that the part fills the table at every distance instead of shrinking to
// a texel or less (a thin limb a few R away vanished from an unzoomed 16²
// table). The cone edge maps to kOvdfZoomEdge, leaving a visible margin whose
// texels hold positive distances. A stored distance D′ (table units) is D′/k
// in plane units (the VDT rule ½ + D/2h is invariant under the uniform
// scale); outside the table, where the held edge value would be too small,
// the cone gives the lower bound D ≥ |p| − e (the occluded set lies in the
// disk), so each shell's distance is max(D′/k, |p| − e). Inside the bounding
// sphere (d ≤ R) k = 1 and there is no bound. The blend of the two shells
// then takes the same bound once more with the cone seen from the receiver
// point itself, which is exact and tighter than the nearer shell's: blending
// cannot spread a shadow beyond it, and a renderer can skip every light whose
// square lies beyond it (src/render/ovdf_lookup.h OvdfLookup::unshadowed).
//
// Lookups run in the occluder's frame (the part's own coordinates).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

#include "src/fields/cpca.h"
#include "src/fields/visibility_map.h"
#include "src/core/mesh.h"
#include "src/shading/ovdf_tables.h"
#include "src/shading/ovdf_small_occluder.h"
#include "src/shading/ovdf_inside.h"

namespace rsl {

// The zoom and cone formulas (kOvdfZoomEdge, kOvdfNoCone, OvdfZoom,
// ovdf_cone_radius: √2·sin(½·asin(R/d)) in square roots only, ovdf_zoom,
// ovdf_plane_distance: max(D′/k, |p| − e)) are the shading core's
// (src/shading/shading_core.h), shared with the GPU's shader.
using shading::kOvdfNoCone;
using shading::kOvdfZoomEdge;
using shading::ovdf_cone_radius;
using shading::ovdf_plane_distance;
using shading::ovdf_zoom;
using shading::OvdfZoom;

enum class ShellSpacing : uint8_t { Geometric = 0, Linear = 1, InverseRadius = 2 };

struct OvdfParams {
    int shells = 16;
    // × bounding radius; 0: chosen per mesh (ovdf_params_for_mesh, which
    // may add shells), resolved by a bake and the field cache before
    // anything else sees it.
    float inner_radius = 0.4f;
    float outer_radius = 6.0f;
    ShellSpacing spacing = ShellSpacing::Geometric;
    int cube_resolution = 32;  // sample points per cube-face side
    int vdt_resolution = 32;
    int vectors = 8;
    int segments_per_side = 2;  // each face split segments_per_side² ways
    int supersampling = 2;
    VdtMode mode = VdtMode::CoverageAware;
    bool half_precision_tables = true;
    uint64_t seed = 1;

    int segment_count() const { return shells * 6 * segments_per_side * segments_per_side; }
    size_t sample_count() const { return size_t(shells) * 6 * cube_resolution * cube_resolution; }
};

// How the eight nearest samples are combined. A sample's VDT stores the part
// as seen from the sample point, centered on its pole. Read in the receiver's
// own pole frame ("aligned"), the first-order effect of moving between samples
// — the part's image sliding across the hemisphere — cancels, and only the
// slow change of the part's silhouette with viewpoint is interpolated. Read in
// each sample's own frame, the image slides by the angle between the sample
// directions (up to half a cube texel, uncorrected at face edges): measured in
// tests/fields/ovdf_test.cpp and docs/design/FIELDS.md.
enum class OvdfBlend : uint8_t {
    AlignedCoefficients = 0,  // per shell: blend the four samples' PCA coefficients, one
                              // reconstruction (four aligned lookups where they straddle segments)
    AlignedSamples = 1,       // eight reconstructions at the receiver's plane point
    SampleFrames = 2,         // eight lookups, each in its sample's own frame
};

struct OvdfBakeStats {
    double seconds = 0;
    size_t rays = 0;
    CpcaReport compression;
};

// Where a receiver point sits among an OVDF's samples: the two shells around
// its distance (clamped inside the inner shell), the cube face and the four
// bilinear sample taps of its direction, and its own pole frame ("aligned",
// twisted by the face rule like the samples). Shared by every lookup path.
struct OvdfLocation {
    int s0 = 0;      // lower shell; the upper one is s0 + 1
    float fs = 0;    // weight of the upper shell
    int face = 0;
    glm::ivec4 ii{0}, jj{0};  // sample taps (i, j) on the face (shading::ovdf_sample_taps)
    Vec4 w{0};                // their bilinear weights
    Frame aligned;               // z = from the point towards the part's center
};

// Many receivers for Ovdf::locate_near, structure of arrays (caller-owned,
// `count` each): points in the occluder's frame in; per point, whether it
// lies between the bounding sphere and the outer shell (`near`: 1) and
// there its bounding cone, blended occluded area and pole out (other points
// need locate()).
struct OvdfNearPoints {
    int count = 0;
    const float *x = nullptr, *y = nullptr, *z = nullptr;
    float *cone = nullptr, *occluded_area = nullptr, *pole_x = nullptr, *pole_y = nullptr, *pole_z = nullptr;
    int32_t* near = nullptr;
};

class Ovdf {
public:
    OvdfParams params;
    Vec3 center{0};
    float radius = 1;  // bounding-sphere radius R
    CpcaModel model;   // samples = shells × 6 × N², clusters = segments
    // Per sample: its signed distance to the part's surface, negative inside
    // (where the table was traced from the surface outside; bake_ovdf). Blended
    // like the tables, it tells a receiver that lies inside the part — a
    // neighbouring part sunk into this one at a joint — which sees nothing.
    std::vector<float> surface_distance;
    // Per sample: the area of its table that the part shadows, in plane
    // units (table area / zoom²), from the traced coverage: the bound of
    // shading::ovdf_area_bound. Empty: no bound.
    std::vector<float> occluded_area;
    // The radial spans (src/fields/ovdf_spans.h): (enter, exit) per radial line
    // of a span_resolution² cube map, interleaved; empty: the surface
    // distances alone decide.
    int span_resolution = 0;
    std::vector<float> radial_span;

    // Set up geometry (radii, frames) for params/center/radius.
    void prepare();

    float shell_radius(int shell) const { return shell_radii_[shell]; }
    const OvdfZoom& shell_zoom(int shell) const { return shell_zoom_[shell]; }
    // Continuous shell index of a distance (linear in the spacing's coordinate).
    float shell_coordinate(float distance) const;
    int sample_index(int shell, int face, int i, int j) const {
        return shading::ovdf_sample_index(shell, face, i, j, params.cube_resolution);
    }
    // shading::ovdf_segment_of with its two divisions read from a table
    // (prepare()): the renderers locate a receiver once per (vertex,
    // occluder), and integer division was a sixth of that.
    int segment_of(int shell, int face, int i, int j) const {
        const int m = params.segments_per_side;
        return ((shell * shading::kCubeFaces + face) * m + segment_column_[size_t(j)]) * m + segment_column_[size_t(i)];
    }
    Vec3 sample_position(int shell, int face, int i, int j) const;
    const Frame& sample_frame(int face, int i, int j) const {
        return frames_[(face * params.cube_resolution + j) * params.cube_resolution + i];
    }

    // Visible fraction, as far as this part occludes, of the square of half-edge
    // `half_edge` around light direction `light` (unit, occluder frame) seen from
    // `point` (occluder frame). 1 beyond the outer shell; clamped to the inner
    // shell inside it. Squares wider than the part's bounding cone take the
    // small-occluder rule, the others the straight-edge rule on distance()
    // bounded by the occluded area, faded between
    // (shading::ovdf_small_occluder_weight).
    float visible_fraction(const Vec3& point, const Vec3& light, float half_edge,
                           OvdfBlend blend = OvdfBlend::AlignedCoefficients) const;

    // The blended signed distance (plane units) that visible_fraction uses.
    float distance(const Vec3& point, const Vec3& light, OvdfBlend blend = OvdfBlend::AlignedCoefficients) const;

    // The samples around `point` (occluder frame) at distance d = |point −
    // center|; callers handle d beyond the outer shell first.
    OvdfLocation locate(const Vec3& point, float d) const;
    // The near half of locate() — bounding cone, blended occluded area,
    // pole — for many points at once, all the small-occluder rule reads
    // (src/fields/ovdf_near.cpp): locate()'s values, in a vectorized loop.
    void locate_near(const OvdfNearPoints& points) const;
    // The blended surface distance at a location: where it is negative within
    // the bounding sphere, the point is inside the part and every lookup is
    // fully shadowed.
    float surface_distance_at(const OvdfLocation& at) const;
    // The samples' occluded areas blended with the lookup's eight weights
    // (kOvdfNoAreaBound for a field without them).
    float occluded_area_at(const OvdfLocation& at) const;
    // Whether a receiver within the bounding sphere (d = |point − center| <
    // radius) lies inside the part: its radial span where that decides,
    // else the blended surface distance (shading::ovdf_span_inside,
    // ovdf_inside_part).
    bool receiver_inside(const Vec3& point, float d, const OvdfLocation& at) const;

    // Distance (plane units) of sample `sample`'s reconstructed VDT at plane
    // point p (its shell's zoom and cone bound applied).
    float sample_distance(int sample, const Vec2& p) const;

private:
    // distance() at a receiver located outside the part (d from the centre,
    // within the outer shell).
    float located_distance(const OvdfLocation& at, float d, const Vec3& light, OvdfBlend blend) const;
    // A per-sample value blended with a lookup's eight weights.
    float blend_samples(const std::vector<float>& per_sample, const OvdfLocation& at) const;

    std::vector<float> shell_radii_;
    std::vector<OvdfZoom> shell_zoom_;
    std::vector<Frame> frames_;                 // per (face, i, j)
    std::vector<int> segment_column_;           // per sample column i: i·m / n, its segment column
    std::array<Vec3, 6> face_normal_{}, face_s_{}, face_t_{};
};

// The shells of a mesh whose parameters leave the inner radius to the bake
// (inner_radius 0, "auto"). Where the bounding sphere's centre lies inside
// the part's solid (a limb, a teapot: src/fields/solid_pieces.h), no receiver
// comes nearer to it than the surface: `shells` shells from 0.4 R (the
// paper's choice) to the outer radius. Where it lies in open space — a
// room's floor and counter, a chair (under its seat), a bowl, a ring —
// receivers can stand anywhere inside the sphere, and a lookup inside the
// inner shell is clamped to it: a chair 0.03–0.2 R from a room's centre was
// looked up on shells 0.4 R away, 98% of its error (docs/design/FIELDS.md). There
// the same shells continue inwards at the same ratio down to 0.03 R or
// below (geometric spacing; the others stop at 0.03 R), so that the part's
// field is as fine near its surface as a solid part's.
OvdfParams ovdf_params_for_mesh(OvdfParams params, const TriangleMesh& mesh);

// Traces and compresses the OVDF of one part (an inner_radius of 0 is
// resolved for the mesh first: the field's params hold the radius used).
Ovdf bake_ovdf(const TriangleMesh& mesh, const OvdfParams& params, OvdfBakeStats* stats = nullptr,
               const std::function<void(double)>& progress = {});

}  // namespace rsl
