#pragma once
// An offscreen OpenGL core-profile context through EGL, for `rsl render
// --backend gl`, the benchmarks and the tests: no window, no X server. It tries
// Mesa's surfaceless platform (llvmpipe or a GPU driver), then the first EGL
// device (NVIDIA's headless path), then the default display; the context is
// made current without a surface (EGL_KHR_surfaceless_context) and every pass
// renders into framebuffer objects. The GPU renderer needs OpenGL 4.3 core
// (compute shaders).
#include <memory>
#include <string>

namespace rsl::gl {

// How the context's EGL config is picked. No surface is ever made, but a
// display without EGL_KHR_no_config_context needs a config for the context.
enum class EglConfig {
    Automatic,  // none where the display allows it, else Chosen
    Chosen,     // always eglChooseConfig: an OpenGL config with pbuffer surfaces, which
                // EGL device displays offer (they have no window surfaces); tests force it
};

class HeadlessContext {
public:
    // Creates a context of at least OpenGL 4.3 core and makes it current on
    // the calling thread. Throws rsl::Error saying, per display, what was
    // tried and what was found.
    explicit HeadlessContext(EglConfig config = EglConfig::Automatic);
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    void make_current();
    // Which EGL platform was used and the GL version/renderer.
    const std::string& description() const { return description_; }

private:
    struct State;
    std::unique_ptr<State> state_;
    std::string description_;
};

}  // namespace rsl::gl
