#include "src/gl/gpu_interface.h"

#include <fmt/format.h>

namespace rsl::gl {

std::string shader_interface_glsl() {
    std::string text = "// Generated from src/gl/gpu_interface.h (shader_interface_glsl).\n";
    for (const GlslConstant& b : kStorageBindings) text += fmt::format("#define {} {}\n", b.name, b.value);
    return text;
}

std::string shader_sampler_declarations() {
    std::string text = "// Generated from src/gl/gpu_interface.h (shader_sampler_declarations).\n";
    for (const Sampler& s : kShadingSamplers) text += fmt::format("uniform {} {};  // {}\n", s.type, s.name, s.comment);
    return text;
}

}  // namespace rsl::gl
