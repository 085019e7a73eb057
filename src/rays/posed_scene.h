#pragma once
// A Scene's parts in a RayScene, posed at a time t. Instance id = mesh id =
// part index. Moving to another time only updates instance transforms and
// re-commits the top level; no part BVH is rebuilt.
#include "src/core/scene.h"
#include "src/core/skinning.h"
#include "src/rays/ray_scene.h"

namespace rsl {

// A mesh vertex in world space: where shadow rays start and the frame the BRDF
// is evaluated in.
struct SurfacePoint {
    Vec3 position{0};
    Vec3 offset_normal{0, 0, 1};  // unit; rays leave on this side (see RayOffset)
    Frame frame;                  // shading frame: z = shading normal, x = tangent
    RayOffset offset;             // its part's (PosedScene::offset)
    // Where its shadow rays start: one offset along offset_normal.
    Vec3 ray_origin() const { return offset.origin(position, offset_normal); }
};

class PosedScene {
public:
    explicit PosedScene(const Scene& scene, float t = 0);  // keeps a reference to `scene`

    void set_time(float t);
    float time() const { return time_; }
    const Scene& scene() const { return scene_; }
    const RayScene& rays() const { return rays_; }
    // A part's ray offset: scaled by its own posed size, not the scene's, as
    // its SVDF's bake (which traces the part alone) scales it, so that no
    // ground elsewhere changes where its rays start (docs/design/TRUTH.md, "Ray offsets").
    RayOffset offset(int part) const { return RayOffset{rays_.instance_diagonal(part)}; }

    const Mat4& part_transform(int part) const { return transforms_[part]; }
    // A skinned part's vertices at time() in its own frame (src/core/skinning.h),
    // traced and shaded in place of its mesh's; null for a rigid part.
    const PosedVertices* skinned(int part) const {
        return skinned_[size_t(part)].positions.empty() ? nullptr : &skinned_[size_t(part)];
    }
    // World-space vertex: position by the part's transform, normal by its
    // inverse transpose, tangent by its linear part (exact also under
    // non-uniform scale), frame by Gram-Schmidt (Frame::from_normal_tangent).
    // A vertex on the border of its surface (a box's face along the ground it
    // stands on) moves by the ray offset into its own triangles, so that it
    // is shaded as its face next to the border, not as a point lying on the
    // other part, whose triangles every ray would hit at t = 0 (docs/design/TRUTH.md).
    SurfacePoint vertex(int part, int vertex) const;
    // World-space point of a primary-ray hit: barycentric position, shading
    // normal and tangent; rays leave on the geometric normal's side that faces
    // the incoming ray.
    SurfacePoint hit_point(const RayHit& hit, const Vec3& ray_direction) const;

private:
    const Scene& scene_;
    RayScene rays_;
    float time_ = 0;
    std::vector<Mat4> transforms_;
    std::vector<Mat3> linear_, normal_;
    std::vector<PosedVertices> skinned_;  // per part; empty for a rigid one
    std::vector<std::vector<Vec3>> inward_;  // per part and vertex: towards its triangles (part frame), or 0
};

}  // namespace rsl
