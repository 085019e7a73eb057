#include "python/numpy_convert.h"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace rsl::python {

namespace {
std::string shape_text(const FloatArray& array) {
    std::vector<py::ssize_t> shape(array.shape(), array.shape() + array.ndim());
    return fmt::format("({})", fmt::join(shape, ", "));
}
}  // namespace

std::vector<float> read_rows(const FloatArray& array, const std::string& what, py::ssize_t columns, py::ssize_t rows) {
    const bool flat = columns == 0;
    const bool shape_ok = flat ? array.ndim() == 1 : array.ndim() == 2 && array.shape(1) == columns;
    if (!shape_ok || (rows >= 0 && array.shape(0) != rows))
        throw Error(fmt::format("{}: expected an array of shape ({}{}), got {}", what, rows >= 0 ? std::to_string(rows) : "N",
                                flat ? "" : fmt::format(", {}", columns), shape_text(array)));
    return std::vector<float>(array.data(), array.data() + array.size());
}

void check_finite(const FloatArray& array, const std::string& where, const std::string& what, bool writing) {
    const float* values = array.data();
    for (py::ssize_t k = 0; k < array.size(); ++k) {
        if (std::isfinite(values[k])) continue;
        std::vector<py::ssize_t> index(size_t(array.ndim()));
        for (py::ssize_t rest = k, d = array.ndim() - 1; d >= 0; --d) {
            index[size_t(d)] = rest % array.shape(d);
            rest /= array.shape(d);
        }
        throw py::value_error(fmt::format("{}: {}[{}] is {} (rsl refuses non-finite values){}", where, what,
                                          fmt::join(index, ", "), std::isnan(values[k]) ? "NaN" : "infinite",
                                          writing ? "; nothing written" : ""));
    }
}

std::vector<api::Float3> read_float3s(const FloatArray& array, const std::string& what) {
    const std::vector<float> values = read_rows(array, what, 3);
    std::vector<api::Float3> out(values.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
    return out;
}

api::Float3 to_float3(const std::vector<float>& values, const std::string& what) {
    if (values.size() != 3) throw Error(fmt::format("{}: expected 3 values, got {}", what, values.size()));
    return {values[0], values[1], values[2]};
}

py::array_t<float> colors_to_numpy(api::VertexColors&& colors) {
    const auto n = py::ssize_t(colors.vertex_count());
    return to_numpy(std::move(colors.rgb), {n, 3});
}

api::VertexColors colors_from_numpy(const FloatArray& array, const std::string& what,
                                    const std::vector<std::string>& part_names,
                                    const std::vector<size_t>& part_offsets) {
    api::VertexColors colors;
    colors.rgb = read_rows(array, what, 3, part_offsets.empty() ? -1 : py::ssize_t(part_offsets.back()));
    colors.part_names = part_names;
    colors.part_offsets = part_offsets;
    if (part_names.empty()) {  // one part of every row
        colors.part_names = {"all"};
        colors.part_offsets = {0, colors.rgb.size() / 3};
    }
    return colors;
}

py::array_t<float> image_to_numpy(api::Image&& image) {
    const py::ssize_t height = image.height, width = image.width;
    return to_numpy(std::move(image.rgba), {height, width, 4});
}

api::Image image_from_numpy(const FloatArray& array, const std::string& what) {
    if (array.ndim() != 3 || array.shape(2) != 4)
        throw Error(fmt::format("{}: expected an RGBA image of shape (height, width, 4), got {}", what, shape_text(array)));
    api::Image image;
    image.height = int(array.shape(0)), image.width = int(array.shape(1));
    image.rgba.assign(array.data(), array.data() + array.size());
    return image;
}

api::Progress progress_callback(const py::object& callable) {
    if (callable.is_none()) return {};
    if (!PyCallable_Check(callable.ptr())) throw Error("progress: expected a callable f(what, fraction) or None");
    // Holds the reference; dropped with the GIL held, whichever thread lets go last.
    struct Holder {
        py::object function;
        ~Holder() {
            py::gil_scoped_acquire gil;
            function = py::object();
        }
    };
    auto holder = std::make_shared<Holder>(Holder{callable});
    return [holder](const std::string& what, double fraction) {
        py::gil_scoped_acquire gil;
        holder->function(what, fraction);
    };
}

}  // namespace rsl::python
