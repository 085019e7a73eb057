#pragma once
// numpy arrays ↔ the public API's types, for the module's files. Arrays
// going out own their data (no copy: the vector moves into a capsule);
// arrays coming in are converted to C-contiguous float32 and their shape is
// checked, with an rsl::Error naming the argument.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "rsl/rsl.h"

namespace rsl::python {

namespace py = pybind11;
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

template <typename T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(std::move(shape), owned->data(), owner);
}

// An (N, columns) float array (columns 0: one dimension, N values); N = -1: any.
std::vector<float> read_rows(const FloatArray& array, const std::string& what, py::ssize_t columns, py::ssize_t rows = -1);
std::vector<api::Float3> read_float3s(const FloatArray& array, const std::string& what);
api::Float3 to_float3(const std::vector<float>& values, const std::string& what);

// Raises ValueError ("WHERE: WHAT[i, j] is NaN …") at the first NaN or
// infinite value of `array`, before anything is formed or (`writing`: WHERE
// is the file) written: rsl's readers refuse files holding one.
void check_finite(const FloatArray& array, const std::string& where, const std::string& what, bool writing);

// (N, 3) colours out; and in, with the renderer's part layout (or one part).
py::array_t<float> colors_to_numpy(api::VertexColors&& colors);
api::VertexColors colors_from_numpy(const FloatArray& array, const std::string& what,
                                    const std::vector<std::string>& part_names,
                                    const std::vector<size_t>& part_offsets);
py::array_t<float> image_to_numpy(api::Image&& image);
api::Image image_from_numpy(const FloatArray& array, const std::string& what);

// A Python callable as a progress callback: called with the GIL held, from
// whatever thread reports; the callable is released with the GIL held too.
api::Progress progress_callback(const py::object& callable);

}  // namespace rsl::python
