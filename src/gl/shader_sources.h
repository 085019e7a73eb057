#pragma once
// GLSL sources of shaders/*.glsl, embedded into the library at build time
// (src/gl/embed_shaders.cmake), so that an installed `rsl` needs no source tree.
#include <string>
#include <string_view>

namespace rsl::gl {

// The text of shaders/<name>, or null when no such shader was embedded.
const char* embedded_shader(std::string_view name);

}  // namespace rsl::gl
