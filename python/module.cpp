// The Python module `rsl` (docs/PYTHON.md): the public C++ API
// (include/rsl/rsl.h) with numpy arrays. Long calls (Renderer(), shade,
// render_image, truth, fit_environment) release the GIL; progress goes to a
// Python callable. rsl.Error carries the message the `rsl` program prints.
#include <fmt/format.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "python/bindings.h"
#include "python/numpy_convert.h"
#include "src/core/memory_limit.h"  // set_memory_limit_setter: the one call past the public API

namespace rsl::python {
namespace {

py::dict build_info_dict() {
    const api::BuildInfo info = api::build_info();
    py::dict d;
    d["version"] = info.version, d["commit"] = info.commit, d["build_type"] = info.build_type;
    d["embree"] = info.embree, d["openexr"] = info.openexr, d["backends"] = info.backends;
    return d;
}

py::dict fit_dict(api::EnvironmentFit&& fit) {
    std::vector<float> centers, half_diagonals, radiance;
    for (const api::SquareLight& l : fit.lights) {
        centers.insert(centers.end(), l.center.begin(), l.center.end());
        half_diagonals.push_back(l.half_diagonal);
        radiance.insert(radiance.end(), l.radiance.begin(), l.radiance.end());
    }
    const auto k = py::ssize_t(fit.lights.size());
    py::dict d;
    d["centers"] = to_numpy(std::move(centers), {k, 3});
    d["half_diagonals"] = to_numpy(std::move(half_diagonals), {k});
    d["radiance"] = to_numpy(std::move(radiance), {k, 3});
    d["resolution"] = fit.resolution;
    d["relative_l2"] = fit.relative_l2;
    d["map_energy"] = fit.map_energy;
    d["light_energy"] = fit.light_energy;
    return d;
}

void bind_files(py::module_& m) {
    m.def("memory_limit", &api::memory_limit,
          "The memory limit (bytes; 0: none) that loading and rendering a scene check their estimate against");
    m.def(
        "set_memory_limit",
        [](const py::object& limit) {
            if (py::isinstance<py::str>(limit)) return api::set_memory_limit(limit.cast<std::string>());
            const std::optional<long long> bytes = int_argument(limit);
            if (!bytes || *bytes < 0)
                throw Error(fmt::format("set_memory_limit {}: expected a number of bytes (0: none) or a size such as "
                                        "'8G' or 'none'", py::isinstance<py::int_>(limit) ? std::string(py::str(limit))
                                                                                          : type_name(limit)));
            api::set_memory_limit(uint64_t(*bytes));
        },
        py::arg("limit"),
        "Set the memory limit: bytes (0: none) or a size such as '8G' or 'none'; shared with the rsl program's "
        "--memory-limit and RSL_MEMORY_LIMIT");
    m.def("build_info", &build_info_dict, "What this module is: version, commit, build type, Embree, OpenEXR, backends");
    m.def(
        "fit_environment",
        [](const std::string& file, int lights, int resolution, bool cross_face) {
            api::EnvironmentFit fit;
            {
                py::gil_scoped_release release;
                fit = api::fit_environment(file, lights, resolution, cross_face);
            }
            return fit_dict(std::move(fit));
        },
        py::arg("file"), py::arg("lights"), py::arg("resolution") = 32, py::arg("cross_face") = true,
        "`rsl fit`: K rotatable square lights of an environment map, as arrays (centers (K, 3), half_diagonals (K,), "
        "radiance (K, 3)) with the map's relative L2 rebuilt from them");
    m.def(
        "bake_fields",
        [](const api::Scene& scene, const py::object& field_cache, const py::object& progress) {
            const std::string folder = field_cache.is_none() ? "" : path_argument(field_cache, "field_cache");
            const api::Progress callback = progress_callback(progress);
            api::SetupReport report;
            {
                py::gil_scoped_release release;
                report = api::bake_fields(scene, folder, callback);
            }
            py::dict d;
            d["fields_loaded"] = report.fields_loaded, d["fields_baked"] = report.fields_baked;
            d["bake_seconds"] = report.bake_seconds;
            return d;
        },
        py::arg("scene"), py::arg("field_cache") = py::none(), py::arg("progress") = py::none(),
        "`rsl bake`: every part's fields into field_cache (None: beside the scene file), baking only what is "
        "missing; returns how many were reused and baked");
    m.def(
        "compare",
        [](const FloatArray& result, const FloatArray& reference) {
            const api::VertexError e = api::compare(colors_from_numpy(result, "result", {}, {}),
                                                    colors_from_numpy(reference, "reference", {}, {}));
            return error_dict(e, false);
        },
        py::arg("result"), py::arg("reference"),
        "`rsl compare` of per-vertex colours ((N, 3) arrays): relative_l2, max_error, relative_max, count");
    m.def(
        "compare_images",
        [](const FloatArray& result, const FloatArray& reference) {
            const api::ImageError e =
                api::compare(image_from_numpy(result, "result"), image_from_numpy(reference, "reference"));
            py::dict d;
            d["relative_l2"] = e.relative_l2, d["relative_h1"] = e.relative_h1, d["max_error"] = e.max_error;
            d["covered"] = e.covered, d["total"] = e.total;
            return d;
        },
        py::arg("result"), py::arg("reference"),
        "`rsl compare` of two RGBA images ((H, W, 4)): over the pixels the reference covers");
    m.def("read_image", [](const std::string& path) { return image_to_numpy(api::read_image(path)); },
          py::arg("path"), "An .exr as an (H, W, 4) float32 array (row 0 at the top)");
    m.def("write_image",
          [](const std::string& path, const FloatArray& image, float exposure, const std::vector<std::string>& inputs) {
              api::Image converted = image_from_numpy(image, "image");
              check_finite(image, path, "image", true);
              api::write_image(path, std::move(converted), exposure, inputs);
          },
          py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0f, py::arg("inputs") = std::vector<std::string>{},
          "Writes an (H, W, 4) image as .exr and a tone-mapped .png beside it (exposure in stops, 0: automatic); "
          "a path that is one of `inputs` (a scene's or renderer's input_files) is refused");
    m.def(
        "read_vertex_colors",
        [](const std::string& path) {
            api::VertexColors colors = api::read_vertex_colors(path);
            py::dict info;
            info["part_names"] = colors.part_names, info["part_offsets"] = colors.part_offsets;
            info["time"] = colors.time, info["scene_name"] = colors.scene_name, info["producer"] = colors.producer;
            return py::make_tuple(colors_to_numpy(std::move(colors)), info);
        },
        py::arg("path"), "An .rslv file (rsl render --vertex-out, rsl truth) as ((N, 3) colours, info dict)");
}

}  // namespace

std::string path_argument(const py::object& value, const char* name) {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::hasattr(value, "__fspath__")) {
        const py::object path = value.attr("__fspath__")();
        if (py::isinstance<py::str>(path)) return path.cast<std::string>();
    }
    throw Error(fmt::format("{}: expected a path (str or os.PathLike), got {}", name, type_name(value)));
}

std::string type_name(const py::handle& value) { return py::str(py::type::handle_of(value).attr("__name__")); }

std::optional<long long> int_argument(const py::handle& value) {
    if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value)) return std::nullopt;
    int overflow = 0;
    const long long number = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0) return std::nullopt;
    return number;
}

int int_argument(const py::handle& value, const std::string& what, int lo, int hi) {
    const std::optional<long long> number = int_argument(value);
    if (number && *number >= lo && *number <= hi) return int(*number);
    const std::string shown = py::isinstance<py::int_>(value) ? std::string(py::str(value)) : type_name(value);
    throw Error(fmt::format("{} {}: expected a whole number from {} to {}", what, shown, lo, hi));
}

std::vector<float> numbers_argument(const py::handle& value, const std::string& what, const char* expected) {
    try {
        if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) return {value.cast<float>()};
        if (!py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value))
            return value.cast<std::vector<float>>();
    } catch (const py::cast_error&) {  // an int past a double's range, a list holding a str
    }
    throw Error(fmt::format("{}: expected {}, got {}", what, expected, type_name(value)));
}

py::dict error_dict(const api::VertexError& e, bool with_objects) {
    py::dict d;
    d["relative_l2"] = e.relative_l2, d["max_error"] = e.max_error, d["relative_max"] = e.relative_max;
    d["count"] = e.count;
    py::dict parts;
    for (size_t p = 0; p < e.part_names.size(); ++p) parts[py::str(e.part_names[p])] = e.part_relative_l2[p];
    d["parts"] = parts;
    if (with_objects && e.object_parts > 0) {
        d["objects"] = e.objects_relative_l2;
        d["worst_part"] = e.worst_part;
        d["worst"] = e.worst_relative_l2;
    }
    return d;
}

}  // namespace rsl::python

PYBIND11_MODULE(rsl, m) {
    using namespace rsl::python;
    m.doc() = "rsl: all-frequency environment lighting of dynamic scenes with rotatable square lights (docs/PYTHON.md)";
    py::register_exception<rsl::Error>(m, "Error", PyExc_RuntimeError);
    py::register_exception<rsl::InternalError>(m, "InternalError", PyExc_RuntimeError);
    m.attr("__version__") = RSL_VERSION_STRING;
    rsl::set_memory_limit_setter("rsl.set_memory_limit");  // the refusal's way out (src/core/memory_limit.h)
    bind_files(m);
    bind_scene(m);
    bind_renderer(m);
}
