// The headless context's chosen-config path: what an EGL device display
// (NVIDIA without an X server) takes, since it has pbuffer configs and no
// window configs. Mesa's displays need no config, so the test forces one.
// Raw GL calls only, so that the test depends on nothing but the context.
#include <catch2/catch.hpp>

#include <array>
#include <string>

#include "src/gl/gl.h"
#include "src/gl/headless_context.h"

namespace rsl {
namespace {

TEST_CASE("a context from a chosen EGL config is OpenGL 4.3 and renders without a surface", "[gl-core]") {
    gl::HeadlessContext context(gl::EglConfig::Chosen);
    INFO(context.description());
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    CHECK(major * 10 + minor >= 43);

    // A clear of a framebuffer object, read back: the surfaceless context draws.
    GLuint framebuffer = 0, color = 0;
    glGenFramebuffers(1, &framebuffer);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    REQUIRE(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    std::array<unsigned char, 4> pixel{};
    glReadPixels(2, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
    CHECK(pixel == std::array<unsigned char, 4>{255, 0, 255, 255});

    // A compute shader writing a storage buffer: what OpenGL 4.3 is needed for.
    const char* source = R"(#version 430
layout(local_size_x = 8) in;
layout(std430, binding = 0) buffer Values { uint values[]; };
void main() { values[gl_GlobalInvocationID.x] = 3u * gl_GlobalInvocationID.x + 1u; })";
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint compiled = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    REQUIRE(compiled == GL_TRUE);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    REQUIRE(linked == GL_TRUE);
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, 16 * sizeof(GLuint), nullptr, GL_STATIC_READ);
    glUseProgram(program);
    glDispatchCompute(2, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::array<GLuint, 16> values{};
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(values), values.data());
    for (GLuint i = 0; i < values.size(); ++i) CHECK(values[i] == 3 * i + 1);
    CHECK(glGetError() == GL_NO_ERROR);

    glUseProgram(0);
    glDeleteProgram(program);
    glDeleteShader(shader);
    glDeleteBuffers(1, &buffer);
    glDeleteRenderbuffers(1, &color);
    glDeleteFramebuffers(1, &framebuffer);
}

}  // namespace
}  // namespace rsl
