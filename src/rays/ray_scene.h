#pragma once
// Embree 3 scene of rigid parts: one BVH per part (built once, in the part's
// frame) placed by instances, so that moving parts change only transforms.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "src/core/math.h"
#include "src/core/mesh.h"
#include "src/shading/ray_samples.h"

namespace rsl {

struct RayHit {
    bool hit = false;
    float t = 0;
    int instance = -1;   // which instance (part)
    int triangle = -1;   // triangle index within the part's mesh
    float u = 0, v = 0;  // barycentrics: p = (1−u−v)·p0 + u·p1 + v·p2
    Vec3 geometric_normal{0};  // world space, unit, (p1−p0)×(p2−p0) orientation
};

// Self-intersection offset for a ray leaving a surface point p on the side of
// the unit normal n (see docs/design/TRUTH.md). The offset is scale-aware: a fixed
// fraction of the scene's size (so a contact between parts leaks only at that
// scale) plus a few float ULPs of |p| (so points far from the origin, whose
// coordinates are coarse, still leave their own surface).
struct RayOffset {
    float scene_scale = 1;  // e.g. the scene's bounding-box diagonal
    static constexpr float kRelativeToScene = shading::kRayOffsetOfScale;
    static constexpr float kRelativeToPosition = shading::kRayOffsetOfPosition;  // ≈ 64 ULPs
    float distance(const Vec3& p) const { return shading::ray_offset_distance(scene_scale, p); }
    Vec3 origin(const Vec3& p, const Vec3& n) const { return p + n * distance(p); }
    // A vertex's: first one offset along `inward` (border_inward_directions:
    // into its own triangles, or 0), then along its normal.
    Vec3 origin(const Vec3& p, const Vec3& n, const Vec3& inward) const { return origin(p + inward * distance(p), n); }
};

// Per vertex of `mesh`, the unit direction into its own triangles within its
// tangent plane where it lies on the border of its surface (a box's face
// along the ground it stands on), else 0: the mean of the directions to its
// triangles' centroids, where those do not cancel. Rays of such a vertex
// start one ray offset along it, so that it is shaded as its face next to
// the border, not as a point on the other part (docs/design/TRUTH.md); the truth
// (PosedScene::vertex) and the SVDF bake both do. Defined in posed_scene.cpp.
std::vector<Vec3> border_inward_directions(const TriangleMesh& mesh);

class RayScene {
public:
    // `origins_outside_surfaces`: occlusion queries ignore a hit within a few
    // ray offsets (RayOffset) of the origin where the ray leaves the hit
    // triangle through its front (counter-clockwise, outward) side, the
    // offset scaled by the hit part's own size (instance_diagonal), not the
    // scene's: a part's self-shadowing must not depend on how large a ground
    // stands elsewhere in the scene, nor differ from its SVDF's bake, which
    // traces the part alone (docs/design/TRUTH.md, "Ray offsets"). An origin
    // that lies on another part's surface — a vertex on the seam where two
    // parts touch — then counts as just outside that part, as the renderer's
    // exact shapes count it; a ray that enters the part there is still
    // blocked (docs/design/TRUTH.md, "Vertices on another part's surface"). The
    // truth's scenes (PosedScene) and the SVDF bake, which trace from
    // vertices, set it; the OVDF bake, which traces from points in space,
    // does not.
    explicit RayScene(bool origins_outside_surfaces = false);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;
    RayScene(RayScene&&) noexcept;
    RayScene& operator=(RayScene&&) noexcept;

    int add_mesh(const TriangleMesh& mesh);                   // → mesh id (prototype BVH)
    int add_instance(int mesh_id, const Mat4& part_to_world);  // → instance id
    // Moves a mesh's vertices (same count, same triangles) and refits its BVH
    // (a skinned part posed anew, src/core/skinning.h); call commit() after.
    void set_mesh_positions(int mesh_id, const std::vector<Vec3>& positions);
    void set_transform(int instance_id, const Mat4& part_to_world);
    void commit();  // after adding or moving; rebuilds only the top level

    int mesh_count() const;
    int instance_count() const;
    int instance_mesh(int instance_id) const;
    const Mat4& instance_transform(int instance_id) const;
    // Diagonal of the world-space bounding box of every instance (after commit).
    float world_diagonal() const;
    // Diagonal of one instance's world-space bounding box (after commit).
    float instance_diagonal(int instance_id) const;

    // Thread-safe queries (after commit). Directions need not be unit for
    // occluded(); t ranges are in units of the direction's length.
    bool occluded(const Vec3& origin, const Vec3& dir, float t_near, float t_far) const;
    RayHit intersect(const Vec3& origin, const Vec3& dir, float t_near = 0,
                     float t_far = 1e30f) const;
    // Coherent packet of rays sharing one origin (the per-vertex case):
    // visible[k] = 1 when dirs[k] reaches t_far unoccluded.
    void occluded_batch(const Vec3& origin, const Vec3* dirs, int count, float t_near, float t_far,
                        uint8_t* visible) const;
    // Rays each from its own origin, in packets of 16 in the given order (so
    // neighbours in the arrays should be coherent: neighbouring origins
    // towards one light, or one origin's rays over one square).
    void occluded_batch(const Vec3* origins, const Vec3* dirs, int count, float t_near, float t_far,
                        uint8_t* visible) const;
    // Same with a t_far per ray (rays towards a sphere light end on its surface).
    void occluded_batch(const Vec3& origin, const Vec3* dirs, const float* t_fars, int count,
                        float t_near, uint8_t* visible) const;

    // Closest hits of one coherent packet of up to kPrimaryPacket rays from a
    // shared origin (a camera's primary rays through neighbouring pixels),
    // directions as structure of arrays: hits[k] is what
    // intersect(origin, dir k) gives (the same hit; u, v and t up to float
    // rounding of Embree's packet kernels). The geometric normal costs a
    // normalization per hit, so it is filled only when asked for (else zero).
    static constexpr int kPrimaryPacket = 16;
    void intersect_packet(const Vec3& origin, const float* dir_x, const float* dir_y, const float* dir_z,
                          int count, RayHit* hits, bool geometric_normals = true) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rsl
