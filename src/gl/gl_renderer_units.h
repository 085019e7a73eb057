#pragma once
// Shared by the GL renderer's translation units (gl_renderer.cpp: the vertex
// pass; gl_display.cpp: the display and per-pixel passes): texture units,
// timed passes, and two small GL helpers.
#include "src/gl/gl_objects.h"

namespace rsl::gl {

// Texture units of the shading inputs (the vertex pass and the per-pixel
// pass bind the same); the per-pixel pass's base colour texture and
// triangle indices last.
enum Unit : int {
    kUnitPositions, kUnitNormals, kUnitTangents, kUnitParts, kUnitLights, kUnitBrdf,
    kUnitBrdfOffsets, kUnitSvdfTables, kUnitSvdfCoefficients, kUnitOvdfTables, kUnitOvdfCoefficients,
    kUnitOvdfFrames, kUnitShadowMaps, kUnitBaseColor, kUnitIndices, kUnitCount
};

// Timed passes (PassTimings), the index of their timer queries.
enum Pass : int { kPassShade, kPassDisplay, kPassShadow, kPassCount };

inline void bind_texture(int unit, GLenum target, GLuint texture) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, texture);
}

inline GLint uniform(const Program& program, const char* name) { return glGetUniformLocation(program.id(), name); }

}  // namespace rsl::gl
