#pragma once
// Embree 3 scene of rigid parts: one BVH per part (built once, in the part's
// frame) placed by instances, so that moving parts change only transforms.
#include <cstdint>
#include <memory>
#include <vector>

#include "src/core/math.h"
#include "src/core/mesh.h"

namespace rsl {

struct RayHit {
    bool hit = false;
    float t = 0;
    int instance = -1;   // which instance (part)
    int triangle = -1;   // triangle index within the part's mesh
    float u = 0, v = 0;  // barycentrics: p = (1−u−v)·p0 + u·p1 + v·p2
};

class RayScene {
public:
    RayScene();
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    int add_mesh(const TriangleMesh& mesh);                   // → mesh id (prototype BVH)
    int add_instance(int mesh_id, const Mat4& part_to_world);  // → instance id
    void set_transform(int instance_id, const Mat4& part_to_world);
    void commit();  // after adding or moving; rebuilds only the top level

    // Thread-safe queries (after commit). Directions need not be unit for
    // occluded(); t ranges are in units of the direction's length.
    bool occluded(const Vec3& origin, const Vec3& dir, float t_near, float t_far) const;
    RayHit intersect(const Vec3& origin, const Vec3& dir, float t_near = 0,
                     float t_far = 1e30f) const;
    // Coherent packet of rays sharing one origin (the per-vertex case):
    // visible[k] = 1 when dirs[k] reaches t_far unoccluded.
    void occluded_batch(const Vec3& origin, const Vec3* dirs, int count, float t_near, float t_far,
                        uint8_t* visible) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rsl
