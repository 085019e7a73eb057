// Embree 3 implementation of RayScene. One RTCScene per mesh (high-quality
// BVH, built once) and a top-level scene of instances; moving a part updates
// its instance transform and re-commits only the top level (a handful of
// instances, microseconds).
#include "src/rays/ray_scene.h"

#include <array>
#include <limits>

#include <embree3/rtcore.h>
#include <glm/gtc/type_ptr.hpp>

#include "src/core/error.h"
#include "src/core/scene_limits.h"

namespace rsl {

namespace {

constexpr int kPacketSize = 16;

void check_device(RTCDevice device, const char* what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) throw_error("Embree error {} during {}", int(error), what);
}

Mat3 normal_matrix(const Mat4& m) { return glm::transpose(glm::inverse(Mat3(m))); }

// What the occlusion filter reads of a mesh: Embree's own copies of its
// buffers (valid while the geometry lives).
struct MeshTriangles {
    const float* positions = nullptr;
    const uint32_t* indices = nullptr;
};

// An occlusion query's context: Embree's, then what tells up to which t a
// hit that leaves its triangle's front side is ignored: 4 ray offsets of the
// hit instance (RayOffset: its scale term, per instance) and of the origin
// (its position term, per ray by its id, the lane), over the direction's length.
struct ExitContext {
    RTCIntersectContext embree;
    bool enabled = false;
    const float* instance_exit = nullptr;  // per instance: 4 · kRelativeToScene · its diagonal
    std::array<float, kPacketSize> position_exit{};  // per lane: 4 · kRelativeToPosition · |origin|∞
    std::array<float, kPacketSize> inverse_length{};
};

// rtcOccluded's filter (RayScene(origins_outside_surfaces = true)). Embree
// passes an instanced mesh's hits with the ray in the mesh's own frame, where
// the triangle's normal is read too; the sign of dot(direction, normal) and
// the ray parameter t are the same in both frames.
void ignore_exits_near_origin(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const ExitContext*>(args->context);
    if (!context->enabled) return;
    const auto* mesh = static_cast<const MeshTriangles*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned lane = RTCRayN_id(args->ray, args->N, i) % unsigned(kPacketSize);
        const unsigned instance = RTCHitN_instID(args->hit, args->N, i, 0);
        const float exit_t = (context->instance_exit[instance] + context->position_exit[lane]) * context->inverse_length[lane];
        if (!(RTCRayN_tfar(args->ray, args->N, i) < exit_t)) continue;
        const uint32_t* tri = mesh->indices + 3 * size_t(RTCHitN_primID(args->hit, args->N, i));
        const Vec3 p0 = glm::make_vec3(mesh->positions + 3 * size_t(tri[0]));
        const Vec3 p1 = glm::make_vec3(mesh->positions + 3 * size_t(tri[1]));
        const Vec3 p2 = glm::make_vec3(mesh->positions + 3 * size_t(tri[2]));
        const Vec3 front = glm::cross(p1 - p0, p2 - p0);
        const Vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                       RTCRayN_dir_z(args->ray, args->N, i));
        if (glm::dot(dir, front) > 0.0f) args->valid[i] = 0;  // leaving the part: the origin is on its surface
    }
}

}  // namespace

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> meshes;
    std::vector<Bounds> mesh_bounds;  // in the mesh's own frame
    std::vector<float*> mesh_vertices;  // per mesh: its Embree vertex buffer (x, y, z per vertex)
    std::vector<size_t> mesh_vertex_count;
    std::vector<RTCGeometry> instances;
    std::vector<int> instance_mesh;
    std::vector<Mat4> transforms;
    std::vector<Mat3> normal_matrices;
    std::vector<std::unique_ptr<MeshTriangles>> mesh_triangles;  // the filter's user data, per mesh
    float world_diagonal = 0;
    std::vector<float> instance_diagonal, instance_exit;  // per instance, after commit
    bool committed = false;
    bool origins_outside_surfaces = false;

    // Up to which t a leaving hit of the ray (origin, dir) is ignored: a few
    // ray offsets (the truth's origins sit one offset off their surface),
    // the hit instance's (ExitContext). Only for a scene made with
    // origins_outside_surfaces (the others, the OVDF bake's among them, skip
    // it: their filter is not even set).
    static constexpr float kExitOffsets = shading::kRayExitOffsets;
    void set_exit(ExitContext& context, int lane, const Vec3& origin, const Vec3& dir) const {
        context.enabled = true;
        context.instance_exit = instance_exit.data();
        const float length = glm::length(dir);
        const float position = RayOffset{0.0f}.distance(origin);  // the position term alone
        context.position_exit[size_t(lane)] = kExitOffsets * position;
        context.inverse_length[size_t(lane)] = length > 0.0f ? 1.0f / length : 0.0f;
    }

    Impl() {
        device = rtcNewDevice(nullptr);
        if (!device) throw_error("Embree: cannot create a device (error {})", int(rtcGetDeviceError(nullptr)));
        top = rtcNewScene(device);
        // Robust: no arithmetic shortcuts that let rays slip between the
        // triangles of a closed mesh (a ground truth must not leak light).
        rtcSetSceneFlags(top, RTC_SCENE_FLAG_ROBUST);
        check_device(device, "scene creation");
    }
    ~Impl() {
        for (RTCGeometry g : instances) rtcReleaseGeometry(g);
        for (RTCScene s : meshes) rtcReleaseScene(s);
        if (top) rtcReleaseScene(top);
        if (device) rtcReleaseDevice(device);
    }

    void require_committed() const {
        if (!committed) throw_error("RayScene: query before commit() (after adding or moving parts)");
    }

    static void init_ray(RTCRay& ray, const Vec3& o, const Vec3& d, float t_near, float t_far) {
        ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z;
        ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
        ray.tnear = t_near;
        ray.tfar = t_far;
        ray.time = 0;
        ray.mask = ~0u;
        ray.id = 0;
        ray.flags = 0;
    }

    // One packet of up to 16 rays from a shared origin o, or (origins not
    // null) each from its own; t_far per ray, or t_far_all.
    void occluded_packet(const Vec3& o, const Vec3* origins, const Vec3* dirs, const float* t_fars, float t_far_all,
                         int count, float t_near, uint8_t* visible) const {
        alignas(64) RTCRay16 ray;
        alignas(64) std::array<int, kPacketSize> valid;
        for (int k = 0; k < kPacketSize; ++k) {
            const bool active = k < count;
            valid[k] = active ? -1 : 0;
            const Vec3 d = active ? dirs[k] : Vec3(0, 0, 1);
            const Vec3 from = origins && active ? origins[k] : o;
            ray.org_x[k] = from.x, ray.org_y[k] = from.y, ray.org_z[k] = from.z;
            ray.dir_x[k] = d.x, ray.dir_y[k] = d.y, ray.dir_z[k] = d.z;
            ray.tnear[k] = t_near;
            ray.tfar[k] = active ? (t_fars ? t_fars[k] : t_far_all) : 0.0f;
            ray.time[k] = 0;
            ray.mask[k] = ~0u;
            ray.id[k] = unsigned(k);
            ray.flags[k] = 0;
        }
        ExitContext context;
        // Deliberately not RTC_INTERSECT_CONTEXT_FLAG_COHERENT: with Embree
        // 3.13.5 and instanced scenes, coherent-mode packets intermittently
        // never return (reproduced: ~50% of runs of a 2-instance scene under
        // TBB hung inside rtcOccluded16; the default flag never did in 30).
        rtcInitIntersectContext(&context.embree);
        if (origins_outside_surfaces)
            for (int k = 0; k < count; ++k) set_exit(context, k, origins ? origins[k] : o, dirs[k]);
        rtcOccluded16(valid.data(), top, &context.embree, &ray);
        // Embree marks an occluded ray by setting tfar to −∞.
        for (int k = 0; k < count; ++k) visible[k] = ray.tfar[k] >= 0.0f ? 1 : 0;
    }
};

RayScene::RayScene(bool origins_outside_surfaces) : impl_(std::make_unique<Impl>()) {
    impl_->origins_outside_surfaces = origins_outside_surfaces;
}
RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

int RayScene::add_mesh(const TriangleMesh& mesh) {
    if (mesh.positions.empty() || mesh.indices.empty() || mesh.indices.size() % 3 != 0)
        throw_error("RayScene: mesh '{}' has no triangles ({} vertices, {} indices)", mesh.name,
                    mesh.positions.size(), mesh.indices.size());
    for (uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw_error("RayScene: mesh '{}' has vertex index {} of {}", mesh.name, index, mesh.positions.size());
    Impl& m = *impl_;
    RTCGeometry geometry = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // rtcSetNewGeometryBuffer pads the buffers as Embree's SIMD loads require.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangle_count()));
    check_device(m.device, "mesh buffer allocation");
    Bounds bounds;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        vertices[3 * i + 0] = mesh.positions[i].x;
        vertices[3 * i + 1] = mesh.positions[i].y;
        vertices[3 * i + 2] = mesh.positions[i].z;
        bounds.extend(mesh.positions[i]);
    }
    std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
    if (m.origins_outside_surfaces) {
        m.mesh_triangles.push_back(std::make_unique<MeshTriangles>(MeshTriangles{vertices, indices}));
        rtcSetGeometryUserData(geometry, m.mesh_triangles.back().get());
        rtcSetGeometryOccludedFilterFunction(geometry, ignore_exits_near_origin);
    }
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(geometry);

    RTCScene scene = rtcNewScene(m.device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    rtcAttachGeometryByID(scene, geometry, 0);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);
    check_device(m.device, "mesh BVH build");
    m.meshes.push_back(scene);
    m.mesh_bounds.push_back(bounds);
    m.mesh_vertices.push_back(vertices);
    m.mesh_vertex_count.push_back(mesh.positions.size());
    return int(m.meshes.size()) - 1;
}

void RayScene::set_mesh_positions(int mesh_id, const std::vector<Vec3>& positions) {
    Impl& m = *impl_;
    RSL_CHECK(mesh_id >= 0 && mesh_id < int(m.meshes.size()));
    RSL_CHECK_EQ(positions.size(), m.mesh_vertex_count[size_t(mesh_id)]);
    float* vertices = m.mesh_vertices[size_t(mesh_id)];
    Bounds bounds;
    for (size_t i = 0; i < positions.size(); ++i) {
        vertices[3 * i + 0] = positions[i].x;
        vertices[3 * i + 1] = positions[i].y;
        vertices[3 * i + 2] = positions[i].z;
        bounds.extend(positions[i]);
    }
    RTCScene scene = m.meshes[size_t(mesh_id)];
    RTCGeometry geometry = rtcGetGeometry(scene, 0);
    rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geometry);
    rtcCommitScene(scene);
    check_device(m.device, "mesh BVH refit");
    m.mesh_bounds[size_t(mesh_id)] = bounds;
    // Instances of the mesh must be re-committed for the top level to see the new bounds.
    for (size_t i = 0; i < m.instances.size(); ++i)
        if (m.instance_mesh[i] == mesh_id) rtcCommitGeometry(m.instances[i]);
    m.committed = false;
}

int RayScene::add_instance(int mesh_id, const Mat4& part_to_world) {
    Impl& m = *impl_;
    RSL_CHECK(mesh_id >= 0 && mesh_id < int(m.meshes.size()));
    RTCGeometry instance = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance, m.meshes[mesh_id]);
    rtcSetGeometryTimeStepCount(instance, 1);
    const int id = int(m.instances.size());
    rtcAttachGeometryByID(m.top, instance, unsigned(id));
    m.instances.push_back(instance);
    m.instance_mesh.push_back(mesh_id);
    m.transforms.emplace_back(1.0f);
    m.normal_matrices.emplace_back(1.0f);
    set_transform(id, part_to_world);
    return id;
}

void RayScene::set_transform(int instance_id, const Mat4& part_to_world) {
    Impl& m = *impl_;
    RSL_CHECK(instance_id >= 0 && instance_id < int(m.instances.size()));
    const float det = glm::determinant(Mat3(part_to_world));
    if (!std::isfinite(det) || std::abs(det) < kMinTransformDeterminant)
        throw_error("RayScene: instance {} has a singular transform (det {})", instance_id, det);
    RTCGeometry instance = m.instances[instance_id];
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(part_to_world));
    rtcCommitGeometry(instance);
    m.transforms[instance_id] = part_to_world;
    m.normal_matrices[instance_id] = normal_matrix(part_to_world);
    m.committed = false;
}

void RayScene::commit() {
    Impl& m = *impl_;
    rtcCommitScene(m.top);
    check_device(m.device, "top-level commit");
    Bounds world;
    m.instance_diagonal.resize(m.instances.size());
    m.instance_exit.resize(m.instances.size());
    for (size_t i = 0; i < m.instances.size(); ++i) {
        const Bounds& b = m.mesh_bounds[m.instance_mesh[i]];
        Bounds instance;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p((corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y,
                         (corner & 4) ? b.hi.z : b.lo.z);
            instance.extend(Vec3(m.transforms[i] * Vec4(p, 1.0f)));
        }
        world.extend(instance.lo), world.extend(instance.hi);
        m.instance_diagonal[i] = glm::length(instance.hi - instance.lo);
        m.instance_exit[i] = Impl::kExitOffsets * RayOffset::kRelativeToScene * m.instance_diagonal[i];
    }
    m.world_diagonal = world.empty() ? 0.0f : glm::length(world.hi - world.lo);
    m.committed = true;
}

int RayScene::mesh_count() const { return int(impl_->meshes.size()); }
int RayScene::instance_count() const { return int(impl_->instances.size()); }
int RayScene::instance_mesh(int instance_id) const { return impl_->instance_mesh.at(instance_id); }
const Mat4& RayScene::instance_transform(int instance_id) const { return impl_->transforms.at(instance_id); }
float RayScene::world_diagonal() const { return impl_->world_diagonal; }
float RayScene::instance_diagonal(int instance_id) const {
    impl_->require_committed();
    return impl_->instance_diagonal.at(size_t(instance_id));
}

bool RayScene::occluded(const Vec3& origin, const Vec3& dir, float t_near, float t_far) const {
    impl_->require_committed();
    RTCRay ray;
    Impl::init_ray(ray, origin, dir, t_near, t_far);
    ExitContext context;
    rtcInitIntersectContext(&context.embree);
    if (impl_->origins_outside_surfaces) impl_->set_exit(context, 0, origin, dir);
    rtcOccluded1(impl_->top, &context.embree, &ray);
    return ray.tfar < 0.0f;
}

RayHit RayScene::intersect(const Vec3& origin, const Vec3& dir, float t_near, float t_far) const {
    impl_->require_committed();
    RTCRayHit query;
    Impl::init_ray(query.ray, origin, dir, t_near, t_far);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(impl_->top, &context, &query);
    RayHit hit;
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.t = query.ray.tfar;
    hit.instance = int(query.hit.instID[0]);
    hit.triangle = int(query.hit.primID);
    hit.u = query.hit.u;
    hit.v = query.hit.v;
    // Embree returns Ng in the instanced mesh's own frame.
    const Vec3 ng_object(query.hit.Ng_x, query.hit.Ng_y, query.hit.Ng_z);
    hit.geometric_normal = glm::normalize(impl_->normal_matrices[hit.instance] * ng_object);
    return hit;
}

void RayScene::occluded_batch(const Vec3& origin, const Vec3* dirs, int count, float t_near, float t_far,
                              uint8_t* visible) const {
    impl_->require_committed();
    for (int start = 0; start < count; start += kPacketSize)
        impl_->occluded_packet(origin, nullptr, dirs + start, nullptr, t_far, std::min(kPacketSize, count - start),
                               t_near, visible + start);
}

void RayScene::occluded_batch(const Vec3* origins, const Vec3* dirs, int count, float t_near, float t_far,
                              uint8_t* visible) const {
    impl_->require_committed();
    for (int start = 0; start < count; start += kPacketSize)
        impl_->occluded_packet(Vec3(0), origins + start, dirs + start, nullptr, t_far,
                               std::min(kPacketSize, count - start), t_near, visible + start);
}

void RayScene::occluded_batch(const Vec3& origin, const Vec3* dirs, const float* t_fars, int count,
                              float t_near, uint8_t* visible) const {
    impl_->require_committed();
    for (int start = 0; start < count; start += kPacketSize)
        impl_->occluded_packet(origin, nullptr, dirs + start, t_fars + start, 0.0f,
                               std::min(kPacketSize, count - start), t_near, visible + start);
}

void RayScene::intersect_packet(const Vec3& origin, const float* dir_x, const float* dir_y, const float* dir_z,
                                int count, RayHit* hits, bool geometric_normals) const {
    impl_->require_committed();
    RSL_CHECK(count >= 0 && count <= kPrimaryPacket);
    static_assert(kPrimaryPacket == 16, "one RTCRayHit16 per packet");
    alignas(64) RTCRayHit16 query;
    alignas(64) std::array<int, kPrimaryPacket> valid;
    for (int k = 0; k < kPrimaryPacket; ++k) {
        const bool active = k < count;
        valid[k] = active ? -1 : 0;
        query.ray.org_x[k] = origin.x, query.ray.org_y[k] = origin.y, query.ray.org_z[k] = origin.z;
        query.ray.dir_x[k] = active ? dir_x[k] : 0.0f;
        query.ray.dir_y[k] = active ? dir_y[k] : 0.0f;
        query.ray.dir_z[k] = active ? dir_z[k] : 1.0f;
        query.ray.tnear[k] = 0.0f;
        query.ray.tfar[k] = active ? 1e30f : 0.0f;  // intersect()'s default range
        query.ray.time[k] = 0;
        query.ray.mask[k] = ~0u;
        query.ray.id[k] = unsigned(k);
        query.ray.flags[k] = 0;
        query.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        query.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
        query.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Coherent: Embree traces the packet's frustum through the BVH, about
    // twice the speed of per-ray traversal for primary rays. The flag hangs
    // rtcOccluded16 (see occluded_packet), not rtcIntersect16: the trace
    // tests' shadow rays traced through rtcIntersect16 with this flag, and
    // 4000 random instanced scenes under TBB, all returned.
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(valid.data(), impl_->top, &context, &query);
    for (int k = 0; k < count; ++k) {
        RayHit& hit = hits[k];
        if (query.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
            hit = RayHit{};
            continue;
        }
        hit.hit = true;
        hit.t = query.ray.tfar[k];
        hit.instance = int(query.hit.instID[0][k]);
        hit.triangle = int(query.hit.primID[k]);
        hit.u = query.hit.u[k];
        hit.v = query.hit.v[k];
        hit.geometric_normal = Vec3(0);
        if (geometric_normals) {
            const Vec3 ng_object(query.hit.Ng_x[k], query.hit.Ng_y[k], query.hit.Ng_z[k]);
            hit.geometric_normal = glm::normalize(impl_->normal_matrices[hit.instance] * ng_object);
        }
    }
}

}  // namespace rsl
