#pragma once
// The module's classes, one file each (module.cpp calls them in order).
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

// compare()'s numbers as a dict, per part under "parts"; with_objects (the
// colours carry the scene's parts: a renderer's compare) adds "objects" and
// "worst_part"/"worst" when some part is not a receiver.
py::dict error_dict(const api::VertexError& error, bool with_objects);

}  // namespace rsl::python
