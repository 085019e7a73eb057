#pragma once
// The module's classes, one file each (module.cpp calls them in order).
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "rsl/rsl.h"

namespace rsl::python {

namespace py = pybind11;

void bind_scene(py::module_& m);     // rsl.Scene (scene_bindings.cpp)
void bind_renderer(py::module_& m);  // rsl.Renderer (renderer_bindings.cpp)

// A pose from translation (3), rotation quaternion (w, x, y, z) and scale (3).
api::Pose pose_from(const std::vector<float>& translation, const std::vector<float>& rotation,
                    const std::vector<float>& scale);

// A file or folder argument: a str or an os.PathLike. Anything else (123)
// is refused, where str() would have made it a folder named "123".
std::string path_argument(const py::object& value, const char* name);

// Arguments that pybind's own casts refuse with "Unable to cast Python
// instance to C++ type" (10**12 for an int, "red" for a float), read here so
// that the error is an rsl.Error naming the argument and what it got.
std::string type_name(const py::handle& value);
// An int (not a bool) that fits in 64 bits; nullopt otherwise.
std::optional<long long> int_argument(const py::handle& value);
// An int within [lo, hi], else rsl.Error "WHAT VALUE: expected a whole number from LO to HI".
int int_argument(const py::handle& value, const std::string& what, int lo, int hi);
// A number or a sequence of numbers, else rsl.Error "WHAT: expected EXPECTED, got TYPE".
std::vector<float> numbers_argument(const py::handle& value, const std::string& what,
                                    const char* expected = "a number or 3 numbers");

// compare()'s numbers as a dict, per part under "parts"; with_objects (the
// colours carry the scene's parts: a renderer's compare) adds "objects" and
// "worst_part"/"worst" when some part is not a receiver.
py::dict error_dict(const api::VertexError& error, bool with_objects);

}  // namespace rsl::python
