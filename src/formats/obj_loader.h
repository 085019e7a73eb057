#pragma once
// Wavefront OBJ meshes, read into the TriangleMesh of src/core/mesh.h.
#include <filesystem>

#include "src/core/mesh.h"

namespace rsl {

// Wavefront OBJ (v, vn, f with any of v, v/t, v//n, v/t/n; negative indices;
// polygons fan-triangulated). Vertices are split where normals differ.
TriangleMesh load_obj(const std::filesystem::path& path);

}  // namespace rsl
