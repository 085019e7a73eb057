#pragma once
// Occluder culling: conservative tests that an occluder part cannot shadow any
// point of a receiver part from a light. Bounding spheres only; a test that
// says "cannot" must be right for every point of the receiver sphere and every
// direction of the light, so that culling never changes an image (pinned by
// tests/render/occluder_culling_test.cpp against brute-force rays).
#include <algorithm>
#include <span>
#include <vector>

#include "src/core/math.h"
#include "src/core/mesh.h"
#include "src/core/scene.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/render/sphere_tree.h"
#include "src/render/square_lights.h"
#include "src/shading/culling.h"

namespace rsl {

// The shared tests (src/shading/culling.h) on BoundingSpheres.
inline Vec4 as_vec4(const BoundingSphere& s) { return Vec4(s.center, s.radius); }
inline BoundingSphere as_sphere(const Vec4& s) { return BoundingSphere{Vec3(s), s.w}; }
inline bool may_shadow_direction(const BoundingSphere& receiver, const BoundingSphere& occluder,
                                 const Vec3& direction, float half_angle) {
    return shading::may_shadow_direction(as_vec4(receiver), as_vec4(occluder), direction, half_angle);
}

// Whether a segment from some point of `receiver` to some point of a sphere
// light (center, radius) can meet `occluder`. The segments lie in the convex
// hull of the two spheres, which lies in the capsule of radius max(r, a)
// around the segment between their centers.
inline bool may_shadow_sphere_light(const BoundingSphere& receiver, const BoundingSphere& occluder,
                                    const Vec3& light_center, float light_radius) {
    const Vec3 axis = light_center - receiver.center;
    const float length2 = glm::dot(axis, axis);
    const Vec3 v = occluder.center - receiver.center;
    const float s = length2 > 0.0f ? std::clamp(glm::dot(v, axis) / length2, 0.0f, 1.0f) : 0.0f;
    const float distance = glm::length(v - s * axis);
    return distance <= std::max(receiver.radius, light_radius) + occluder.radius;
}

inline bool beyond_reach(const BoundingSphere& receiver, const BoundingSphere& reach) {
    return shading::beyond_reach(as_vec4(receiver), as_vec4(reach));
}
inline BoundingSphere transform_sphere(const Mat4& m, const BoundingSphere& s) {
    return as_sphere(shading::transform_sphere(m, as_vec4(s)));
}

// A part as the per-frame occluder culling sees it: its occluder field (null:
// casts no shadow through lookups) with that field's reach in the part's own
// frame, and its pose at the current time.
struct CullingPart {
    const OccluderField* field = nullptr;
    BoundingSphere local_reach;
    Mat4 transform{1.0f};
    BoundingSphere world_bounds;
};

// The lights of one frame: environment squares (world space) first, then the
// local sphere lights at `light_positions` (radii from `lights`).
struct CullingLights {
    std::span<const SquareLight> environment;
    std::span<const Vec3> light_positions;
    std::span<const LocalLight> lights;
};

// The per-frame occluder lists, shared by the CPU renderer and the GL frame
// state so that both run exactly the same lookups.
//   occluders[offsets[p·L + l] .. offsets[p·L + l + 1]): the occluder parts
//   whose lookups run for receiver part p and light l (L lights in all), in
//   ascending part order;
//   growth[e]: how much occluder occluders[e]'s field footprint grows the
//   receiver in culling tests (world units; 0 without culling).
// With culling, a receiver's candidates come from a sphere tree over the
// occluders' field reaches (sphere_tree.h), so a frame costs O(P log P +
// the pairs within reach), not O(P²). Reusing one OccluderLists across
// frames does not allocate once its vectors have grown.
struct OccluderLists {
    std::vector<int> occluders;
    std::vector<float> growth;
    std::vector<size_t> offsets;
    size_t pairs = 0;   // (receiver, occluder, light) triples considered
    size_t culled = 0;  // ... of which culled
    // Per receiver: the occluders whose reach it lies in (before the per-light
    // tests), summed over receivers: what the search hands the light tests.
    size_t candidates = 0;
    // Per receiver p, the same as candidates (the GPU's blocks start from
    // them, gpu_layout.h pack_block_candidates): its candidates
    // [candidate_offsets[p], candidate_offsets[p + 1]) in ascending part
    // order, each with its growth and `light_words` words of light bits, bit
    // l set where light l's list keeps it.
    std::vector<size_t> candidate_offsets;
    std::vector<int> candidate_occluders;
    std::vector<float> candidate_growths;
    std::vector<uint32_t> candidate_lights;
    size_t light_words = 0;

    // Scratch of update_occluder_lists.
    SphereTree reach_tree;
    std::vector<BoundingSphere> reaches;  // per part with a field, world space
    std::vector<int> field_parts;         // the parts with a field, ascending
    std::vector<int> candidate_parts;
    std::vector<float> candidate_growth;
};

// Fills `out` for the parts and lights of one frame. Without culling every
// other part with a field is listed; lights switched off by `options` (and all
// lights without options.occluders) list none.
void update_occluder_lists(std::span<const CullingPart> parts, const CullingLights& lights,
                           const RenderOptions& options, OccluderLists& out);

}  // namespace rsl
