#pragma once
// The API tests' scene: the generated orb on a small floor grid, under the
// generated sun and sky turning at 40°/s, with light precomputation (bakes in
// well under a second), written as a JSON scene file into a scratch folder so
// that the `rsl` program and the API read the same file and field cache.
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "tests/test_support.h"

namespace rsl::test {

struct ApiSceneOptions {
    std::string orb_transform = "{}";     // the orb's "transform" object
    std::string environment_rotation = R"({ "axis": [0, 1, 0], "degrees": 30, "degrees_per_second": 40 })";
    std::string floor_albedo = "[0.55, 0.53, 0.5]";
    std::string camera = R"("position": [0.9, 0.75, 1.3], "target": [0, 0.2, 0])";
};

// A floor of (n + 1)² vertices over [−half, half]² at y = 0, as OBJ text.
inline std::string floor_obj(int n, float half) {
    std::string obj;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            obj += fmt::format("v {} 0 {}\n", -half + 2 * half * i / n, -half + 2 * half * j / n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;  // OBJ counts from 1
            obj += fmt::format("f {} {} {}\nf {} {} {}\n", a, c, b, b, c, d);
        }
    return obj;
}

// Subdivision off: api::Mesh carries no tangents, so a mesh subdivided at
// load (its tangents interpolated from the loaded ones) and the same mesh
// added in code (tangents generated afresh) turn their light squares
// differently, and the built-vs-loaded test compares bit for bit.
inline std::filesystem::path write_api_scene(const std::filesystem::path& folder, const std::string& file_name,
                                             const ApiSceneOptions& o = {}) {
    const std::string generated = std::string(RSL_SOURCE_DIR) + "/assets/generated";
    if (!std::filesystem::exists(folder / "floor.obj")) write_text(folder / "floor.obj", floor_obj(32, 0.8f));
    const std::filesystem::path path = folder / file_name;
    write_text(path, fmt::format(R"({{
  "name": "api-test",
  "parts": [
    {{ "name": "orb", "obj": "{0}/orb.obj", "material": "steel", "transform": {1} }},
    {{ "name": "floor", "obj": "floor.obj", "material": "floor" }}
  ],
  "materials": {{
    "steel": {{ "model": "phong", "kd": [0.3, 0.3, 0.32], "ks": [0.4, 0.4, 0.4], "exponent": 30 }},
    "floor": {{ "model": "lambert", "albedo": {3} }},
    "clay":  {{ "model": "lambert", "albedo": [0.7, 0.4, 0.3] }}
  }},
  "environment": {{ "file": "{0}/sunsky.exr", "resolution": 12, "rotation": {2} }},
  "camera": {{ {4}, "up": [0, 1, 0], "fov_degrees": 36, "width": 96, "height": 72 }},
  "animation": {{ "start": 0, "end": 1, "fps": 24 }},
  "subdivision": false,
  "precompute": {{
    "svdf": {{ "resolution": 8, "clusters": 16, "vectors": 4, "supersampling": 1 }},
    "ovdf": {{ "shells": 4, "inner_radius": 0.4, "outer_radius": 6.0, "cube_resolution": 6, "vdt_resolution": 8, "vectors": 4 }}
  }}
}}
)", generated, o.orb_transform, o.environment_rotation, o.floor_albedo, o.camera));
    return path;
}

}  // namespace rsl::test
