#include "src/rays/posed_scene.h"

#include "src/core/error.h"
#include "src/core/scene_limits.h"

namespace rsl {

std::vector<Vec3> border_inward_directions(const TriangleMesh& mesh) {
    std::vector<Vec3> sum(mesh.vertex_count(), Vec3(0));
    std::vector<float> length(mesh.vertex_count(), 0.0f);
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const uint32_t* tri = &mesh.indices[t];
        const Vec3 centroid = (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0f;
        for (int k = 0; k < 3; ++k) {
            const Vec3 d = centroid - mesh.positions[tri[k]];
            sum[tri[k]] += d;
            length[tri[k]] += glm::length(d);
        }
    }
    for (size_t v = 0; v < sum.size(); ++v) {
        const Vec3 n = mesh.normals[v];
        const Vec3 in_plane = sum[v] - n * glm::dot(n, sum[v]);
        const float size = glm::length(in_plane);
        sum[v] = size > 0.25f * length[v] && size > 0.0f ? in_plane / size : Vec3(0);
    }
    return sum;
}

PosedScene::PosedScene(const Scene& scene, float t) : scene_(scene), rays_(/*origins_outside_surfaces=*/true) {
    if (scene.parts.empty()) throw_file_error(scene.source, "scene '{}' has no parts", scene.name);
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const int mesh = rays_.add_mesh(scene.parts[p].mesh);
        const int instance = rays_.add_instance(mesh, Mat4(1.0f));
        RSL_CHECK(mesh == int(p) && instance == int(p));
        inward_.push_back(border_inward_directions(scene.parts[p].mesh));
    }
    skinned_.resize(scene.parts.size());
    transforms_.resize(scene.parts.size());
    linear_.resize(scene.parts.size());
    normal_.resize(scene.parts.size());
    set_time(t);
}

void PosedScene::set_time(float t) {
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const Mat4 m = scene_.part_transform_at(int(p), t);
        check_part_pose(scene_, int(p), t, m);
        transforms_[p] = m;
        linear_[p] = Mat3(m);
        normal_[p] = glm::transpose(glm::inverse(Mat3(m)));
        rays_.set_transform(int(p), m);
        if (scene_.parts[p].skin) {
            pose_skinned_part(scene_, int(p), t, skinned_[p]);
            rays_.set_mesh_positions(int(p), skinned_[p].positions);
        }
    }
    rays_.commit();
    time_ = t;
}

SurfacePoint PosedScene::vertex(int part, int v) const {
    const TriangleMesh& mesh = scene_.parts[part].mesh;
    const PosedVertices* posed = skinned(part);
    const Vec3& position = posed ? posed->positions[size_t(v)] : mesh.positions[size_t(v)];
    const Vec3& normal = posed ? posed->normals[size_t(v)] : mesh.normals[size_t(v)];
    SurfacePoint x;
    x.position = Vec3(transforms_[part] * Vec4(position, 1.0f));
    const Vec3 n = glm::normalize(normal_[part] * normal);
    const Vec3 t = mesh.tangents.empty() ? Vec3(0)
                   : posed               ? linear_[part] * Vec3(posed->tangents[size_t(v)])
                                         : linear_[part] * Vec3(mesh.tangents[size_t(v)]);
    x.frame = Frame::from_normal_tangent(n, t);
    x.offset_normal = x.frame.z;
    x.offset = offset(part);
    const Vec3 inward = inward_[size_t(part)][size_t(v)];
    if (inward != Vec3(0)) x.position += glm::normalize(linear_[part] * inward) * x.offset.distance(x.position);
    return x;
}

SurfacePoint PosedScene::hit_point(const RayHit& hit, const Vec3& ray_direction) const {
    RSL_CHECK(hit.hit);
    const TriangleMesh& mesh = scene_.parts[hit.instance].mesh;
    const PosedVertices* posed = skinned(hit.instance);
    const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
    const float w0 = 1.0f - hit.u - hit.v, w1 = hit.u, w2 = hit.v;
    auto blend = [&](const auto& values) {
        return w0 * Vec3(values[tri[0]]) + w1 * Vec3(values[tri[1]]) + w2 * Vec3(values[tri[2]]);
    };
    SurfacePoint x;
    x.position = Vec3(transforms_[hit.instance] * Vec4(blend(posed ? posed->positions : mesh.positions), 1.0f));
    Vec3 n = glm::normalize(normal_[hit.instance] * blend(posed ? posed->normals : mesh.normals));
    const Vec3 t = mesh.tangents.empty() ? Vec3(0)
                                         : linear_[hit.instance] * blend(posed ? posed->tangents : mesh.tangents);
    const bool front = glm::dot(hit.geometric_normal, ray_direction) < 0;
    x.offset_normal = front ? hit.geometric_normal : -hit.geometric_normal;
    // A back face seen through a hole or an open mesh: shade the side we see.
    if (glm::dot(n, x.offset_normal) < 0) n = -n;
    x.frame = Frame::from_normal_tangent(n, t);
    x.offset = offset(hit.instance);
    return x;
}

}  // namespace rsl
