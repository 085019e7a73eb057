// rsl.Scene: load a scene file, or build one from numpy meshes.
#include <limits>

#include <pybind11/stl.h>

#include <fmt/format.h>

#include "python/bindings.h"
#include "python/numpy_convert.h"

namespace rsl::python {
namespace {

using IndexArray = py::array_t<uint32_t, py::array::c_style | py::array::forcecast>;

api::Camera camera_from(const std::vector<float>& position, const std::vector<float>& target,
                        const std::vector<float>& up, float fov_y_degrees, int width, int height) {
    return {to_float3(position, "camera position"), to_float3(target, "camera target"), to_float3(up, "camera up"),
            fov_y_degrees, width, height};
}

// Material parameters from keyword arguments: a number or a sequence of numbers each.
std::map<std::string, std::vector<float>> parameters_from(const py::kwargs& kwargs) {
    std::map<std::string, std::vector<float>> parameters;
    for (const auto& [key, value] : kwargs) {
        const std::string name = py::str(key);
        parameters[name] = numbers_argument(value, fmt::format("material parameter '{}'", name));
    }
    return parameters;
}

api::Precompute precompute_from(const py::kwargs& kwargs, api::Precompute p) {
    for (const auto& item : kwargs) {
        const py::handle value = item.second;  // a plain name: lambdas cannot capture structured bindings under Clang 14
        const std::string name = py::str(item.first);
        const std::string what = "set_precompute " + name;
        const auto setting = [&] { return int_argument(value, what, 0, std::numeric_limits<int>::max()); };
        const auto radius = [&] {
            const std::vector<float> r = numbers_argument(value, what, "a number");
            if (r.size() != 1) throw Error(fmt::format("{}: expected a number, got {} numbers", what, r.size()));
            return r[0];
        };
        if (name == "svdf_resolution") p.svdf_resolution = setting();
        else if (name == "svdf_clusters") p.svdf_clusters = setting();
        else if (name == "svdf_vectors") p.svdf_vectors = setting();
        else if (name == "svdf_supersampling") p.svdf_supersampling = setting();
        else if (name == "ovdf_shells") p.ovdf_shells = setting();
        else if (name == "ovdf_inner_radius") p.ovdf_inner_radius = radius();
        else if (name == "ovdf_outer_radius") p.ovdf_outer_radius = radius();
        else if (name == "ovdf_cube_resolution") p.ovdf_cube_resolution = setting();
        else if (name == "ovdf_vdt_resolution") p.ovdf_vdt_resolution = setting();
        else if (name == "ovdf_vectors") p.ovdf_vectors = setting();
        else throw Error(fmt::format("set_precompute: unknown setting '{}'", name));
    }
    return p;
}

py::dict precompute_dict(const api::Precompute& p) {
    py::dict d;
    d["svdf_resolution"] = p.svdf_resolution, d["svdf_clusters"] = p.svdf_clusters;
    d["svdf_vectors"] = p.svdf_vectors, d["svdf_supersampling"] = p.svdf_supersampling;
    d["ovdf_shells"] = p.ovdf_shells, d["ovdf_inner_radius"] = p.ovdf_inner_radius;
    d["ovdf_outer_radius"] = p.ovdf_outer_radius, d["ovdf_cube_resolution"] = p.ovdf_cube_resolution;
    d["ovdf_vdt_resolution"] = p.ovdf_vdt_resolution, d["ovdf_vectors"] = p.ovdf_vectors;
    return d;
}

}  // namespace

api::Pose pose_from(const std::vector<float>& translation, const std::vector<float>& rotation,
                    const std::vector<float>& scale) {
    if (rotation.size() != 4) throw Error(fmt::format("rotation: expected a quaternion (w, x, y, z), got {} values", rotation.size()));
    return {to_float3(translation, "translation"), {rotation[0], rotation[1], rotation[2], rotation[3]},
            to_float3(scale, "scale")};
}

void bind_scene(py::module_& m) {
    py::class_<api::Scene>(m, "Scene", "A scene: rigid parts, materials, an environment map, sphere lights, a camera")
        .def(py::init<const std::string&>(), py::arg("name") = "scene", "An empty scene to build in code")
        .def_static("load", &api::Scene::load, py::arg("path"), py::call_guard<py::gil_scoped_release>(),
                    "A JSON scene file, .gltf/.glb or .obj (docs/SCENE_FORMAT.md)")
        .def("add_material",
             [](api::Scene& s, const std::string& name, const std::string& model, const std::string& file,
                const py::kwargs& parameters) {
                 return s.add_material({name, model, parameters_from(parameters), file});
             },
             py::arg("name"), py::arg("model") = "lambert", py::arg("file") = "",
             "A BRDF by model and parameters as keywords, e.g. add_material('floor', 'lambert', albedo=(0.5, 0.5, 0.5))")
        .def("add_part",
             [](api::Scene& s, const std::string& name, const FloatArray& positions, const IndexArray& triangles,
                const std::string& material, const py::object& normals, const std::vector<float>& translation,
                const std::vector<float>& rotation, const std::vector<float>& scale) {
                 api::Mesh mesh;
                 mesh.positions = read_float3s(positions, "positions");
                 if (triangles.ndim() != 2 || triangles.shape(1) != 3)
                     throw Error("triangles: expected an (M, 3) array of vertex indices");
                 mesh.indices.assign(triangles.data(), triangles.data() + triangles.size());
                 if (!normals.is_none()) mesh.normals = read_float3s(normals.cast<FloatArray>(), "normals");
                 return s.add_part(name, mesh, material, pose_from(translation, rotation, scale));
             },
             py::arg("name"), py::arg("positions"), py::arg("triangles"), py::arg("material"),
             py::arg("normals") = py::none(), py::arg("translation") = std::vector<float>{0, 0, 0},
             py::arg("rotation") = std::vector<float>{1, 0, 0, 0}, py::arg("scale") = std::vector<float>{1, 1, 1},
             "A rigid part from (V, 3) positions and (M, 3) triangles; returns its index")
        .def("set_environment", &api::Scene::set_environment, py::arg("file"), py::arg("resolution") = 32)
        .def("set_environment_rotation",
             [](api::Scene& s, const std::vector<float>& axis, float degrees, float per_second) {
                 s.set_environment_rotation(to_float3(axis, "axis"), degrees, per_second);
             },
             py::arg("axis"), py::arg("degrees"), py::arg("degrees_per_second") = 0.0f)
        .def("add_sphere_light",
             [](api::Scene& s, const std::vector<float>& position, float radius, const std::vector<float>& power) {
                 s.add_sphere_light({to_float3(position, "position"), radius, to_float3(power, "power")});
             },
             py::arg("position"), py::arg("radius") = 0.05f, py::arg("power") = std::vector<float>{1, 1, 1})
        .def("set_camera",
             [](api::Scene& s, const std::vector<float>& position, const std::vector<float>& target,
                const std::vector<float>& up, float fov, int width, int height) {
                 s.set_camera(camera_from(position, target, up, fov, width, height));
             },
             py::arg("position"), py::arg("target"), py::arg("up") = std::vector<float>{0, 1, 0},
             py::arg("fov_y_degrees") = 40.0f, py::arg("width") = 640, py::arg("height") = 480)
        .def("set_precompute",
             [](api::Scene& s, const py::kwargs& settings) { s.set_precompute(precompute_from(settings, s.precompute())); },
             "Field precomputation settings by keyword (the keys of `precompute`)")
        .def_property_readonly("precompute", [](const api::Scene& s) { return precompute_dict(s.precompute()); })
        .def_property_readonly("name", &api::Scene::name)
        .def_property_readonly("part_names", &api::Scene::part_names)
        .def_property_readonly("input_files", &api::Scene::input_files,
                               "The files it was read from (scene file, meshes, maps), which no write may replace")
        .def_property_readonly("material_names", &api::Scene::material_names)
        .def_property_readonly("part_vertex_counts", &api::Scene::part_vertex_counts)
        .def_property_readonly("vertex_count", &api::Scene::vertex_count)
        .def_property_readonly("environment_file", &api::Scene::environment_file)
        .def_property_readonly("environment_resolution", &api::Scene::environment_resolution)
        .def("part_mesh",
             [](const api::Scene& s, int part) {
                 api::Mesh mesh = s.part_mesh(part);
                 std::vector<float> positions, normals;
                 for (const auto& p : mesh.positions) positions.insert(positions.end(), p.begin(), p.end());
                 for (const auto& n : mesh.normals) normals.insert(normals.end(), n.begin(), n.end());
                 const auto v = py::ssize_t(mesh.positions.size()), t = py::ssize_t(mesh.indices.size() / 3);
                 return py::make_tuple(to_numpy(std::move(positions), {v, 3}), to_numpy(std::move(mesh.indices), {t, 3}),
                                       to_numpy(std::move(normals), {v, 3}));
             },
             py::arg("part"), "(positions (V, 3), triangles (M, 3), normals (V, 3)) in the part's frame");
}

}  // namespace rsl::python
