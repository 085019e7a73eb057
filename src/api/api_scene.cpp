// rsl::api::Scene and Pose (include/rsl/rsl.h): a scene from a file through
// load_scene, or built in code into the same rsl::Scene a file gives.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "src/api/api_convert.h"
#include "src/core/emission.h"
#include "src/core/envmap.h"
#include "src/core/mesh.h"
#include "src/core/precompute_limits.h"
#include "src/formats/scene_file.h"

namespace rsl::api {

Pose Pose::from_matrix(const std::array<float, 16>& m) {
    Mat4 matrix;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(m[4 * c + r])) throw_error("pose matrix: entry ({}, {}) is not finite", r, c);
            matrix[c][r] = m[4 * c + r];
        }
    if (matrix[0][3] != 0 || matrix[1][3] != 0 || matrix[2][3] != 0 || matrix[3][3] != 1)
        throw_error("pose matrix: the last row is ({}, {}, {}, {}), expected (0, 0, 0, 1): a projection is no pose",
                    matrix[0][3], matrix[1][3], matrix[2][3], matrix[3][3]);
    Mat3 linear(matrix);
    Vec3 scale(glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2]));
    if (scale.x == 0 || scale.y == 0 || scale.z == 0) throw_error("pose matrix: a column of zero length");
    if (glm::determinant(linear) < 0)
        throw_error("pose matrix: a mirror (negative determinant) would turn the part inside out");
    const Mat3 rotation(linear[0] / scale.x, linear[1] / scale.y, linear[2] / scale.z);
    // Shear leaves the columns unequal to a rotation's: R^T·R must be I.
    const Mat3 gram = glm::transpose(rotation) * rotation;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (std::abs(gram[c][r] - (r == c ? 1.0f : 0.0f)) > 1e-4f)
                throw_error("pose matrix: not translation · rotation · scale (its columns are not orthogonal: shear)");
    const Quat q = glm::normalize(glm::quat_cast(rotation));
    Pose pose;
    pose.translation = to_float3(Vec3(matrix[3]));
    pose.rotation = {q.w, q.x, q.y, q.z};
    pose.scale = to_float3(scale);
    return pose;
}

Scene::Scene(const std::string& name) : scene_(std::make_unique<rsl::Scene>()) {
    scene_->name = name;
    scene_->animation = {0, 0, 24};
}
Scene Scene::load(const std::string& path) {
    Scene scene;
    *scene.scene_ = load_scene(path);
    return scene;
}
Scene::Scene(const Scene& other) : scene_(std::make_unique<rsl::Scene>(*other.scene_)) {}
Scene& Scene::operator=(const Scene& other) {
    if (this != &other) scene_ = std::make_unique<rsl::Scene>(*other.scene_);
    return *this;
}
Scene::Scene(Scene&& other) noexcept = default;
Scene& Scene::operator=(Scene&& other) noexcept = default;
Scene::~Scene() = default;

int Scene::add_material(const Material& material) {
    if (material.name.empty()) throw_error("material: no name");
    for (const MaterialDesc& m : scene_->materials)
        if (m.name == material.name) throw_error("material '{}': the scene has one of that name", material.name);
    MaterialDesc desc;
    desc.name = material.name;
    desc.model = material.model;
    desc.params = material.parameters;
    desc.file = material.file;
    if (auto it = desc.params.find("emissive"); it != desc.params.end()) {  // not a BRDF parameter (src/core/emission.h)
        desc.emissive = checked_emission(desc.name, it->second);
        desc.params.erase(it);
    }
    scene_->materials.push_back(std::move(desc));
    return int(scene_->materials.size()) - 1;
}

int Scene::add_part(const std::string& name, const Mesh& mesh, const std::string& material, const Pose& pose) {
    const std::string what = fmt::format("part '{}'", name);
    int material_index = -1;
    for (size_t m = 0; m < scene_->materials.size(); ++m)
        if (scene_->materials[m].name == material) material_index = int(m);
    if (material_index < 0) throw_error("{}: no material '{}' (add_material first)", what, material);
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
        throw_error("{}: {} normals for {} positions", what, mesh.normals.size(), mesh.positions.size());
    Part part;
    part.name = name;
    part.mesh.name = name;
    for (const Float3& p : mesh.positions) part.mesh.positions.push_back(to_vec3(p));
    for (const Float3& n : mesh.normals) part.mesh.normals.push_back(to_vec3(n));
    part.mesh.indices = mesh.indices;
    validate_and_complete(part.mesh, what);  // throws "part 'NAME': …" like a file's "PATH: …"
    SceneNode node;
    node.name = name;
    node.rest = to_transform(pose, what + " pose");
    scene_->nodes.push_back(node);
    part.node = int(scene_->nodes.size()) - 1;
    part.material = material_index;
    scene_->parts.push_back(std::move(part));
    return int(scene_->parts.size()) - 1;
}

void Scene::set_environment(const std::string& file, int resolution) {
    if (resolution < 1 || resolution > kMaxCubeResolution)
        throw_error("environment resolution {}: expected 1..{} texels per cube-face edge", resolution,
                    kMaxCubeResolution);
    scene_->environment.file = file;
    scene_->environment.resolution = resolution;
}

void Scene::set_environment_rotation(const Float3& axis, float degrees, float degrees_per_second) {
    set_rotation(scene_->environment, axis, degrees, degrees_per_second);
}

void Scene::add_sphere_light(const SphereLight& light) {
    if (!(light.radius > 0)) throw_error("sphere light radius {}: expected > 0", light.radius);
    scene_->lights.push_back(to_local_light(light));
}

void Scene::set_camera(const Camera& camera) { scene_->camera = to_camera(camera); }

void Scene::set_precompute(const Precompute& s) {
    if (!(s.ovdf_inner_radius >= 0 && s.ovdf_outer_radius > s.ovdf_inner_radius && std::isfinite(s.ovdf_outer_radius)))
        throw_error("precompute: OVDF shells from {} to {} bounding radii, expected 0 ≤ inner < outer (0: per mesh)",
                    s.ovdf_inner_radius, s.ovdf_outer_radius);
    PrecomputeSettings p;
    p.svdf_resolution = s.svdf_resolution, p.svdf_clusters = s.svdf_clusters, p.svdf_vectors = s.svdf_vectors;
    p.svdf_supersampling = s.svdf_supersampling;
    p.ovdf_shells = s.ovdf_shells, p.ovdf_inner_radius = s.ovdf_inner_radius, p.ovdf_outer_radius = s.ovdf_outer_radius;
    p.ovdf_cube_resolution = s.ovdf_cube_resolution, p.ovdf_vdt_resolution = s.ovdf_vdt_resolution;
    p.ovdf_vectors = s.ovdf_vectors;
    // The scene file's rules, its key spelt as the setting's name here ("svdf_resolution").
    if (const auto problem = precompute_problem(p)) {
        std::string name = problem->key;
        std::replace(name.begin(), name.end(), '.', '_');
        throw_error("precompute: {} {}", name, problem->message);
    }
    scene_->precompute = p;
}

std::string Scene::name() const { return scene_->name; }

std::vector<std::string> Scene::part_names() const {
    std::vector<std::string> names;
    for (const Part& part : scene_->parts) names.push_back(part.name);
    return names;
}

std::vector<std::string> Scene::material_names() const {
    std::vector<std::string> names;
    for (const MaterialDesc& m : scene_->materials) names.push_back(m.name);
    return names;
}

std::vector<size_t> Scene::part_vertex_counts() const {
    std::vector<size_t> counts;
    for (const Part& part : scene_->parts) counts.push_back(part.mesh.vertex_count());
    return counts;
}

size_t Scene::vertex_count() const { return scene_->vertex_count(); }

Camera Scene::camera() const {
    const ::rsl::Camera& c = scene_->camera;
    return {to_float3(c.position_at(0)), to_float3(c.target_at(0)), to_float3(c.up), c.fov_y_degrees, c.width,
            c.height};
}

Mesh Scene::part_mesh(int part) const {
    if (part < 0 || part >= int(scene_->parts.size()))
        throw_error("part {}: the scene has {} parts", part, scene_->parts.size());
    const TriangleMesh& m = scene_->parts[part].mesh;
    Mesh mesh;
    for (const Vec3& p : m.positions) mesh.positions.push_back(to_float3(p));
    for (const Vec3& n : m.normals) mesh.normals.push_back(to_float3(n));
    mesh.indices = m.indices;
    return mesh;
}

Precompute Scene::precompute() const {
    const PrecomputeSettings& p = scene_->precompute;
    return {p.svdf_resolution,    p.svdf_clusters,        p.svdf_vectors,        p.svdf_supersampling,
            p.ovdf_shells,        p.ovdf_inner_radius,    p.ovdf_outer_radius,   p.ovdf_cube_resolution,
            p.ovdf_vdt_resolution, p.ovdf_vectors};
}

std::string Scene::environment_file() const { return scene_->environment.file.string(); }
int Scene::environment_resolution() const { return scene_->environment.resolution; }

std::vector<std::string> Scene::input_files() const { return ::rsl::api::input_files(*scene_); }

}  // namespace rsl::api
