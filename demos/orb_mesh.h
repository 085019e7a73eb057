#pragma once
// The materials and compare demos' object, "orb": a sphere inside a tilted
// ring. Small (a few thousand vertices), round enough to show a highlight's
// shape, and it shadows itself (ring on sphere, sphere on ring), so the SVDF
// matters. demos/materials/orb.obj is this mesh, written by `rsl demo orb-mesh`.
#include <filesystem>

#include "src/core/mesh.h"

namespace rsl::demos {

// Resting on y = 0 (the sphere touches the floor), centered on the Y axis.
TriangleMesh make_orb_mesh();

// Wavefront OBJ with positions and normals (5 significant digits), written atomically.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const std::string& comment);

}  // namespace rsl::demos
