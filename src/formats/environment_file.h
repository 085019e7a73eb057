#pragma once
// Environment files: an OpenEXR or Radiance .hdr image, a 2:1 latitude-
// longitude map or a 1:6 vertical cube strip (docs/SCENE_FORMAT.md), read
// into the cube map of src/core/envmap.h.
#include <filesystem>

#include "src/core/envmap.h"

namespace rsl {

// Any supported environment file (.exr or .hdr; lat-long 2:1 or cube strip 1:6) → cube map.
CubeMap load_environment(const std::filesystem::path& path, int n);

}  // namespace rsl
