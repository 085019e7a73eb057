// rsl.Renderer: a frame of a scene to numpy arrays, its ground truth, and the
// per-frame changes. The GIL is released while it shades, forms images,
// traces the truth and while it is made (fit and field bakes); a mutex per
// renderer makes calls from several Python threads take turns.
#include <mutex>

#include <pybind11/stl.h>

#include <fmt/format.h>

#include "python/bindings.h"
#include "python/numpy_convert.h"

namespace rsl::python {
namespace {

int part_index(const std::vector<std::string>& names, const std::string& scene, const py::object& part) {
    if (py::isinstance<py::int_>(part) && !py::isinstance<py::bool_>(part)) {
        const std::optional<long long> index = int_argument(part);
        if (index && *index >= 0 && *index < static_cast<long long>(names.size())) return int(*index);
        throw Error(fmt::format("part {}: scene '{}' has {} parts", std::string(py::str(part)), scene, names.size()));
    }
    if (!py::isinstance<py::str>(part))
        throw Error(fmt::format("part: expected an index or a name, got {}", type_name(part)));
    const std::string name = part.cast<std::string>();
    for (size_t p = 0; p < names.size(); ++p)
        if (names[p] == name) return int(p);
    throw Error(fmt::format("no part '{}' (parts: {})", name, fmt::join(names, ", ")));
}

std::vector<size_t> part_offsets(const api::Scene& scene) {
    std::vector<size_t> offsets{0};
    for (size_t n : scene.part_vertex_counts()) offsets.push_back(offsets.back() + n);
    return offsets;
}

// The Renderer with what Python needs besides: the vertex layout of its
// scene (fixed when it is made, so read without the lock).
struct PyRenderer {
    PyRenderer(api::Renderer r, std::string name, std::vector<std::string> names, std::vector<size_t> offsets)
        : renderer(std::move(r)), scene_name(std::move(name)), part_names(std::move(names)),
          part_offsets(std::move(offsets)) {}

    api::VertexColors colors(const FloatArray& array, const std::string& what) const {
        return colors_from_numpy(array, what, part_names, part_offsets);
    }

    // Runs f(renderer) with the GIL released and the renderer's lock held:
    // the GIL first, since a call holding the lock may need the GIL for a
    // progress callback while another thread waits for the lock.
    template <typename F>
    auto locked(F&& f) {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(mutex);
        return f(renderer);
    }
    template <typename F>
    auto locked(F&& f) const {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(mutex);
        return f(static_cast<const api::Renderer&>(renderer));
    }

    api::Renderer renderer;
    const std::string scene_name;
    const std::vector<std::string> part_names;
    const std::vector<size_t> part_offsets;
    mutable std::mutex mutex;
};

std::unique_ptr<PyRenderer> make_renderer(const api::Scene& scene, int lights, const std::string& backend,
                                          const py::object& field_cache, bool cross_face, bool self_visibility,
                                          bool occluders, const std::map<std::string, std::string>& part_materials,
                                          const py::object& progress, const std::string& pixel_shadows,
                                          bool pixel_highlights, int ray_samples, bool exact_diffuse_light) {
    api::RenderSettings settings;
    settings.lights = lights;
    settings.backend = backend;
    settings.ray_samples = ray_samples;
    if (!field_cache.is_none()) settings.field_cache = path_argument(field_cache, "field_cache");
    settings.cross_face_lights = cross_face;
    settings.self_visibility = self_visibility;
    settings.occluders = occluders;
    settings.pixel_shadows = pixel_shadows;
    settings.pixel_highlights = pixel_highlights;
    settings.exact_diffuse_light = exact_diffuse_light;
    settings.part_materials = part_materials;
    settings.progress = progress_callback(progress);
    py::gil_scoped_release release;
    api::Renderer renderer(scene, settings);
    return std::make_unique<PyRenderer>(std::move(renderer), scene.name(), scene.part_names(), part_offsets(scene));
}

py::dict lights_dict(const std::vector<api::SquareLight>& lights) {
    std::vector<float> centers, half_diagonals, radiance;
    for (const api::SquareLight& l : lights) {
        centers.insert(centers.end(), l.center.begin(), l.center.end());
        half_diagonals.push_back(l.half_diagonal);
        radiance.insert(radiance.end(), l.radiance.begin(), l.radiance.end());
    }
    const auto k = py::ssize_t(lights.size());
    py::dict d;
    d["centers"] = to_numpy(std::move(centers), {k, 3});
    d["half_diagonals"] = to_numpy(std::move(half_diagonals), {k});
    d["radiance"] = to_numpy(std::move(radiance), {k, 3});
    return d;
}

std::vector<api::SquareLight> lights_from(const FloatArray& centers, const FloatArray& half_diagonals,
                                          const FloatArray& radiance) {
    const std::vector<api::Float3> c = read_float3s(centers, "centers");
    const std::vector<float> r = read_rows(half_diagonals, "half_diagonals", 0, py::ssize_t(c.size()));
    const std::vector<float> i = read_rows(radiance, "radiance", 3, py::ssize_t(c.size()));
    std::vector<api::SquareLight> lights(c.size());
    for (size_t k = 0; k < c.size(); ++k) lights[k] = {c[k], r[k], {i[3 * k], i[3 * k + 1], i[3 * k + 2]}};
    return lights;
}

api::ImageSettings image_settings(int width, int height, int samples) { return {width, height, samples}; }

}  // namespace

void bind_renderer(py::module_& m) {
    py::class_<PyRenderer>(m, "Renderer", "The RSL renderer of one scene (its own copy), as `rsl render` runs it")
        .def(py::init(&make_renderer), py::arg("scene"), py::arg("lights") = 30, py::arg("backend") = "cpu",
             py::arg("field_cache") = py::none(), py::arg("cross_face_lights") = true,
             py::arg("self_visibility") = true, py::arg("occluders") = true,
             py::arg("part_materials") = std::map<std::string, std::string>{}, py::arg("progress") = py::none(),
             py::arg("pixel_shadows") = "planes", py::arg("pixel_highlights") = true, py::arg("ray_samples") = 1,
             py::arg("exact_diffuse_light") = true,
             "Fits `lights` square lights to the environment and loads or bakes the fields (field_cache: a "
             "folder; None: beside the scene file). backend: cpu, rays (every light's visibility from "
             "ray_samples x ray_samples shadow rays per vertex, no fields), gl, gl-current (build_info()"
             "['backends'] lists this module's). progress(what, fraction) hears the fit and the bakes. "
             "pixel_shadows: which parts' render_image() takes the other parts' shadows per pixel (planes, "
             "all, off), as `rsl render --pixel-shadows`; pixel_highlights: glossy parts take the BRDF per "
             "pixel there; exact_diffuse_light: the diffuse term takes the environment's exact irradiance, the "
             "squares giving its shadows (False: the RSL paper's sum), as `rsl render --exact-diffuse-light`.")
        .def_property_readonly("backend",
                               [](const PyRenderer& r) { return r.locked([](const auto& x) { return x.backend(); }); })
        .def_property_readonly("device",
                               [](const PyRenderer& r) { return r.locked([](const auto& x) { return x.device(); }); })
        .def_property_readonly("part_names", [](const PyRenderer& r) { return r.part_names; })
        .def_property_readonly("input_files",
                               [](const PyRenderer& r) { return r.locked([](const auto& x) { return x.input_files(); }); },
                               "The files its scene was read from, which no write may replace")
        .def_property_readonly("part_offsets", [](const PyRenderer& r) { return r.part_offsets; },
                               "Part p is rows part_offsets[p]:part_offsets[p + 1] of the colour arrays")
        .def_property_readonly("setup",
                               [](const PyRenderer& r) {
                                   const api::SetupReport s = r.locked([](const auto& x) { return x.setup(); });
                                   py::dict d;
                                   d["lights"] = s.lights, d["fields_loaded"] = s.fields_loaded;
                                   d["fields_baked"] = s.fields_baked, d["fit_seconds"] = s.fit_seconds;
                                   d["bake_seconds"] = s.bake_seconds;
                                   return d;
                               })
        .def_property("time", [](const PyRenderer& r) { return r.locked([](const auto& x) { return x.time(); }); },
                      [](PyRenderer& r, float t) { r.locked([t](auto& x) { x.set_time(t); }); })
        .def("set_time", [](PyRenderer& r, float t) { r.locked([t](auto& x) { x.set_time(t); }); }, py::arg("t"))
        .def("set_part_pose",
             [](PyRenderer& r, const py::object& part, const std::vector<float>& translation,
                const std::vector<float>& rotation, const std::vector<float>& scale, const py::object& matrix) {
                 api::Pose pose = pose_from(translation, rotation, scale);
                 if (!matrix.is_none()) {
                     const std::vector<float> rows = read_rows(matrix.cast<FloatArray>(), "matrix", 4, 4);
                     std::array<float, 16> column_major;
                     for (int c = 0; c < 4; ++c)
                         for (int row = 0; row < 4; ++row) column_major[4 * c + row] = rows[4 * row + c];
                     pose = api::Pose::from_matrix(column_major);
                 }
                 const int index = part_index(r.part_names, r.scene_name, part);
                 r.locked([&](auto& x) { x.set_part_pose(index, pose); });
             },
             py::arg("part"), py::arg("translation") = std::vector<float>{0, 0, 0},
             py::arg("rotation") = std::vector<float>{1, 0, 0, 0}, py::arg("scale") = std::vector<float>{1, 1, 1},
             py::arg("matrix") = py::none(),
             "Puts a part (index or name) at a world pose from now on: translation, rotation (w, x, y, z), scale, "
             "or a 4×4 matrix (numpy row-major, M @ [x, y, z, 1])")
        .def("part_transform",
             [](const PyRenderer& r, const py::object& part) {
                 const int index = part_index(r.part_names, r.scene_name, part);
                 const std::array<float, 16> c = r.locked([&](const auto& x) { return x.part_transform(index); });
                 std::vector<float> rows(16);
                 for (int col = 0; col < 4; ++col)
                     for (int row = 0; row < 4; ++row) rows[4 * row + col] = c[4 * col + row];
                 return to_numpy(std::move(rows), {4, 4});
             },
             py::arg("part"), "The part's world matrix at the current frame (4×4, row-major)")
        .def("set_environment_rotation",
             [](PyRenderer& r, const std::vector<float>& axis, float degrees) {
                 const api::Float3 a = to_float3(axis, "axis");
                 r.locked([&](auto& x) { x.set_environment_rotation(a, degrees); });
             },
             py::arg("axis"), py::arg("degrees"))
        .def("set_camera",
             [](PyRenderer& r, const std::vector<float>& position, const std::vector<float>& target,
                const std::vector<float>& up, float fov, int width, int height) {
                 const api::Camera camera{to_float3(position, "camera position"),
                                                  to_float3(target, "camera target"), to_float3(up, "camera up"), fov,
                                                  width, height};
                 r.locked([&](auto& x) { x.set_camera(camera); });
             },
             py::arg("position"), py::arg("target"), py::arg("up") = std::vector<float>{0, 1, 0},
             py::arg("fov_y_degrees") = 40.0f, py::arg("width") = 640, py::arg("height") = 480)
        .def("set_sphere_lights",
             [](PyRenderer& r, const FloatArray& positions, const FloatArray& radii, const FloatArray& powers) {
                 const std::vector<api::Float3> p = read_float3s(positions, "positions");
                 const std::vector<float> a = read_rows(radii, "radii", 0, py::ssize_t(p.size()));
                 const std::vector<float> w = read_rows(powers, "powers", 3, py::ssize_t(p.size()));
                 std::vector<api::SphereLight> lights(p.size());
                 for (size_t i = 0; i < p.size(); ++i) lights[i] = {p[i], a[i], {w[3 * i], w[3 * i + 1], w[3 * i + 2]}};
                 r.locked([&](auto& x) { x.set_sphere_lights(lights); });
             },
             py::arg("positions"), py::arg("radii"), py::arg("powers"))
        .def_property_readonly("environment_lights",
                               [](const PyRenderer& r) {
                                   return lights_dict(r.locked([](const auto& x) { return x.environment_lights(); }));
                               })
        .def("set_environment_lights",
             [](PyRenderer& r, const FloatArray& centers, const FloatArray& half_diagonals, const FloatArray& radiance) {
                 const std::vector<api::SquareLight> lights = lights_from(centers, half_diagonals, radiance);
                 r.locked([&](auto& x) { x.set_environment_lights(lights); });
             },
             py::arg("centers"), py::arg("half_diagonals"), py::arg("radiance"),
             "The environment's square lights, e.g. fit_environment(...)'s arrays")
        .def("set_part_material",
             [](PyRenderer& r, const std::string& part, const std::string& material) {
                 r.locked([&](auto& x) { x.set_part_material(part, material); });
             },
             py::arg("part"), py::arg("material"))
        .def("set_material_parameter",
             [](PyRenderer& r, const std::string& material, const std::string& key, const py::object& value) {
                 const std::vector<float> values = numbers_argument(value, fmt::format("set_material_parameter '{}'", key));
                 r.locked([&](auto& x) { x.set_material_parameter(material, key, values); });
             },
             py::arg("material"), py::arg("key"), py::arg("value"))
        .def("shade",
             [](PyRenderer& r) {
                 return colors_to_numpy(r.locked([](auto& x) { return x.shade(); }));
             },
             "Per-vertex colours of the current frame, (N, 3) float32, parts in order (part_offsets)")
        .def("form_image",
             [](const PyRenderer& r, const FloatArray& colors, int width, int height, int samples) {
                 const api::VertexColors c = r.colors(colors, "colors");
                 check_finite(colors, "form_image", "colors", false);
                 return image_to_numpy(
                     r.locked([&](const auto& x) { return x.form_image(c, image_settings(width, height, samples)); }));
             },
             py::arg("colors"), py::arg("width") = 0, py::arg("height") = 0, py::arg("samples") = 1,
             "The (H, W, 4) image of (N, 3) vertex colours, as rsl render forms it (0: the camera's size)")
        .def("render_image",
             [](PyRenderer& r, int width, int height, int samples) {
                 return image_to_numpy(
                     r.locked([&](auto& x) { return x.render_image(image_settings(width, height, samples)); }));
             },
             py::arg("width") = 0, py::arg("height") = 0, py::arg("samples") = 1,
             "The image as `rsl render -o` makes it, (H, W, 4): shade(), then the image with the per-pixel "
             "passes (the renderer's pixel_shadows and pixel_highlights); form_image(shade()) draws the "
             "vertex colours alone")
        .def("truth",
             [](const PyRenderer& r, int subdivision, bool local_lights, const py::object& progress) {
                 api::TruthSettings settings{subdivision, local_lights, progress_callback(progress)};
                 return colors_to_numpy(r.locked([&](const auto& x) { return x.truth(settings); }));
             },
             py::arg("subdivision") = 1, py::arg("local_lights") = true, py::arg("progress") = py::none(),
             "The Embree ground truth of the current frame (rsl truth), (N, 3)")
        .def("compare",
             [](const PyRenderer& r, const FloatArray& result, const FloatArray& reference,
                const std::vector<std::string>& receivers) {
                 return error_dict(api::compare(r.colors(result, "result"), r.colors(reference, "reference"), receivers),
                                   true);
             },
             py::arg("result"), py::arg("reference"), py::arg("receivers") = std::vector<std::string>{"ground", "floor", "plane"},
             "rsl compare of (N, 3) colours, with the error of each part, of the objects (every part but the "
             "receivers) and the worst part")
        .def("write_vertex_colors",
             [](const PyRenderer& r, const std::string& path, const FloatArray& colors, const std::string& producer) {
                 api::VertexColors c = r.colors(colors, "colors");
                 check_finite(colors, path, "colors", true);
                 c.producer = producer;
                 c.scene_name = r.scene_name;
                 r.locked([&](const auto& x) {
                     c.time = x.time();
                     api::write_vertex_colors(path, c, x.input_files());
                 });
             },
             py::arg("path"), py::arg("colors"), py::arg("producer") = "python",
             "Writes (N, 3) colours of this scene as an .rslv file (for rsl compare); a path that is one of its "
             "scene's input_files is refused");
}

}  // namespace rsl::python
