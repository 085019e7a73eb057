#pragma once
// Shared by the GL renderer's translation units (gl_renderer.cpp: the vertex
// pass; gl_display.cpp: the display and per-pixel passes): timed passes,
// and two small GL helpers. Texture units and bindings: gpu_interface.h.
#include "src/gl/gl_objects.h"
#include "src/gl/gpu_interface.h"

namespace rsl::gl {

// Timed passes (PassTimings), the index of their timer queries.
enum Pass : int { kPassShade, kPassDisplay, kPassShadow, kPassCount };

inline void bind_texture(int unit, GLenum target, GLuint texture) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, texture);
}

inline GLint uniform(const Program& program, const char* name) { return glGetUniformLocation(program.id(), name); }

}  // namespace rsl::gl
