#pragma once
// The OpenGL API as rsl uses it: the core-profile header with prototypes. The
// entry points come from libglvnd's libOpenGL.so (Debian's Mesa and NVIDIA's
// driver both install it), which dispatches to whichever context — EGL or GLX
// — is current, so no loader library is needed. Everything used is core 4.3
// (compute shaders, storage buffers), except glClipControl (4.5), which is
// called only where the context has it (GlRenderer::form_image).
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace rsl::gl {

// Throws rsl::Error when the GL error flag is set, naming `what`.
void check_gl(const char* what);

// "OpenGL 4.5 (Core Profile) Mesa 22.3.6 on llvmpipe (...)" of the current context.
std::string context_description();
// Whether the current context renders in software on the CPU (Mesa's
// llvmpipe, softpipe or swrast, from GL_RENDERER): frames cost seconds.
bool is_software_renderer();
// Whether a context (EGL or GLX) is current on this thread: libglvnd's
// dispatch answers glGetString with null when none is.
bool has_current_context();

}  // namespace rsl::gl
