#pragma once
// An offscreen OpenGL core-profile context through EGL, for `rsl render
// --backend gl`, the benchmarks and the tests: no window, no X server. It tries
// Mesa's surfaceless platform (llvmpipe or a GPU driver), then the first EGL
// device (NVIDIA's headless path), then the default display; the context is
// made current without a surface (EGL_KHR_surfaceless_context) and every pass
// renders into framebuffer objects.
#include <memory>
#include <string>

namespace rsl::gl {

class HeadlessContext {
public:
    // Creates a context of at least OpenGL 3.3 core and makes it current on
    // the calling thread. Throws rsl::Error saying what was tried.
    HeadlessContext();
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
