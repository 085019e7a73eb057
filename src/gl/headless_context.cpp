#include "src/gl/headless_context.h"

#include <cstring>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "src/core/error.h"
#include "src/gl/gl.h"

namespace rsl::gl {

struct HeadlessContext::State {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

namespace {

bool has_extension(const char* extensions, const char* name) {
    if (!extensions) return false;
    const size_t length = std::strlen(name);
    for (const char* p = std::strstr(extensions, name); p; p = std::strstr(p + 1, name))
        if ((p == extensions || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0')) return true;
    return false;
}

// Displays to try, best first, with the platform's name.
std::vector<std::pair<EGLDisplay, std::string>> candidate_displays() {
    std::vector<std::pair<EGLDisplay, std::string>> displays;
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY) displays.emplace_back(d, "EGL surfaceless");
    }
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (get_platform_display && query_devices && has_extension(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (query_devices(8, devices, &count))
            for (EGLint i = 0; i < count; ++i) {
                EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (d != EGL_NO_DISPLAY) displays.emplace_back(d, "EGL device " + std::to_string(i));
            }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY) displays.emplace_back(d, "EGL default display");
    return displays;
}

// An OpenGL config for a display that cannot make a context without one. Its
// surface type is never used (the context is made current without a surface),
// but eglChooseConfig defaults EGL_SURFACE_TYPE to EGL_WINDOW_BIT, and an EGL
// device display (NVIDIA without X) has no window configs: ask for pbuffer
// configs, as NVIDIA's headless EGL examples do, then for any surface type.
EGLConfig choose_config(EGLDisplay display) {
    for (const EGLint surface_type : {EGLint(EGL_PBUFFER_BIT), EGLint(EGL_DONT_CARE)}) {
        const EGLint attributes[] = {EGL_SURFACE_TYPE, surface_type, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = EGL_NO_CONFIG_KHR;
        EGLint count = 0;
        if (eglChooseConfig(display, attributes, &config, 1, &count) && count > 0) return config;
    }
    return EGL_NO_CONFIG_KHR;
}

EGLContext create_core_context(EGLDisplay display, EglConfig choice) {
    if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    const bool configless = choice == EglConfig::Automatic &&
                            (has_extension(extensions, "EGL_KHR_no_config_context") ||
                             has_extension(extensions, "EGL_MESA_configless_context"));
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!configless && (config = choose_config(display)) == EGL_NO_CONFIG_KHR) return EGL_NO_CONTEXT;
    // The newest core version first: drivers give the newest they can anyway,
    // but some refuse a request above what they support. Versions below 4.3
    // are asked for too, so that an older driver's context can say in the
    // error which version it has.
    const EGLint versions[][2] = {{4, 6}, {4, 5}, {4, 3}, {4, 1}, {3, 3}};
    for (const auto& version : versions) {
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     version[0],
                                     EGL_CONTEXT_MINOR_VERSION,
                                     version[1],
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
        EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
        if (context != EGL_NO_CONTEXT) return context;
    }
    return EGL_NO_CONTEXT;
}

// Whether the current context is OpenGL 4.3 or newer (compute shaders).
bool has_gl_4_3() {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    return major > 4 || (major == 4 && minor >= 3);
}

}  // namespace

HeadlessContext::HeadlessContext(EglConfig config) : state_(std::make_unique<State>()) {
    std::string tried;
    for (const auto& [display, name] : candidate_displays()) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            tried += fmt::format("\n  {}: eglInitialize failed (0x{:x})", name, eglGetError());
            continue;
        }
        const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
        if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
            tried += fmt::format("\n  {}: no EGL_KHR_surfaceless_context", name);
            eglTerminate(display);
            continue;
        }
        EGLContext context = create_core_context(display, config);
        if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            tried += fmt::format("\n  {}: no OpenGL ≥ 4.3 core context (0x{:x})", name, eglGetError());
            if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
            eglTerminate(display);
            continue;
        }
        if (!has_gl_4_3()) {
            tried += fmt::format("\n  {}: {} found, OpenGL ≥ 4.3 core needed", name, context_description());
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context);
            eglTerminate(display);
            continue;
        }
        state_->display = display;
        state_->context = context;
        description_ = name + ": " + context_description();
        return;
    }
    throw Error("no headless OpenGL context: tried" + (tried.empty() ? std::string(" no EGL display") : tried));
}

HeadlessContext::~HeadlessContext() {
    if (state_->context != EGL_NO_CONTEXT) {
        eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(state_->display, state_->context);
    }
    // The display is left initialized: other contexts in this process may share it.
}

void HeadlessContext::make_current() {
    if (!eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context))
        throw Error(fmt::format("eglMakeCurrent failed (0x{:x})", eglGetError()));
}

}  // namespace rsl::gl
