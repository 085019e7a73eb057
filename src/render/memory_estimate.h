#pragma once
// The peak memory of preparing and rendering a scene, estimated from its
// counts before anything large is allocated, so that a scene too large for
// the machine is refused with a clear error instead of running out of memory
// (src/core/memory_limit.h; docs/SCENE_FORMAT.md, "Memory").
#include <cstdint>
#include <string>

#include "src/core/scene.h"

namespace rsl {

struct MemoryEstimate {
    uint64_t bytes = 0;
    std::string what;  // the counts that drive it, for messages
};

// The renderer's estimate: the parts' vertices (meshes, per-vertex state),
// the fields of each unique mesh, resident and while baking, the BRDF
// tables, the light fit of the environment maps, and the image (a side of 0:
// the scene camera's).
MemoryEstimate estimate_render_memory(const Scene& scene, bool self_visibility, bool occluders, int image_width = 0,
                                      int image_height = 0);

// Throws rsl::Error naming the scene's file when the estimate passes the limit.
void check_render_memory(const Scene& scene, bool self_visibility, bool occluders, int image_width = 0,
                         int image_height = 0);

}  // namespace rsl
