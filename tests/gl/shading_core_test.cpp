// The shading core's two compilations agree: every shared function of
// src/shading/shading_core.h (through the cases of shading_core_cases.h) runs
// in a tiny fragment shader over fixed-seed random inputs, one fragment per
// case, and its results are compared with the C++ compilation's (integers
// exactly, floats to rounding: see close()). A formula
// that only one side could see (a macro, a GLSL built-in that differs from
// std::, a literal without its `f`) shows up here with both values printed.
#include <catch2/catch.hpp>

#include <fstream>
#include <random>
#include <sstream>

#include "src/core/envmap.h"
#include "src/gl/gl_objects.h"
#include "src/gl/shader_sources.h"
#include "tests/gl/gl_test_support.h"
#include "tests/gl/shading_core_cases.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

constexpr int kSide = 64;  // 4096 cases per mode

// The text of tests/gl/shading_core_cases.h between its GLSL markers.
std::string cases_glsl() {
    std::ifstream in(std::string(RSL_SOURCE_DIR) + "/tests/gl/shading_core_cases.h");
    REQUIRE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    const size_t begin = s.find("// RSL_GLSL_BEGIN"), end = s.find("// RSL_GLSL_END");
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    return s.substr(begin, end - begin);
}

// The fragment shader: the renderer's prelude (layout constants and the
// shading core, exactly as the shading pass gets them), the cases, and a
// main that evaluates one case per fragment into two float targets.
std::string fragment_source() {
    return "#version 330 core\n" + gl::shading_prelude() + "#line 1 2\n" + cases_glsl() +
           "#line 1 3\n"
           "uniform sampler2D u_a;\n"
           "uniform sampler2D u_b;\n"
           "uniform int u_mode;\n"
           "uniform vec3 u_normals[6];\n"
           "uniform vec3 u_s[6];\n"
           "uniform vec3 u_t[6];\n"
           "layout(location = 0) out vec4 o_first;\n"
           "layout(location = 1) out vec4 o_second;\n"
           "void main() {\n"
           "    ivec2 texel = ivec2(gl_FragCoord.xy);\n"
           "    CaseOutput o = shading_core_case(u_mode, texelFetch(u_a, texel, 0), texelFetch(u_b, texel, 0),\n"
           "                                     u_normals, u_s, u_t);\n"
           "    o_first = o.first;\n"
           "    o_second = o.second;\n"
           "}\n";
}

gl::Texture float_texture(const std::vector<Vec4>* data) {
    gl::Texture texture = gl::make_texture();
    glBindTexture(GL_TEXTURE_2D, texture.id());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kSide, kSide, 0, GL_RGBA, GL_FLOAT, data ? data->data() : nullptr);
    return texture;
}

// Float rounding only: the driver's normalize (an inverse square root),
// dot products and fused multiply-adds round differently from glm, and a
// few outputs amplify that (a bilinear weight is a coordinate of up to ~90
// minus its integer part; Gram–Schmidt of a nearly parallel tangent), so
// 2·10⁻⁵ of max(1, |value|). A formula that differs misses it by far more,
// in most of the 4096 cases.
bool close(float gpu, float cpu, float condition = 1.0f) {
    if (std::isnan(cpu) || std::isnan(gpu)) return std::isnan(cpu) && std::isnan(gpu);
    return std::abs(gpu - cpu) <= 2e-5f * condition * std::max(1.0f, std::abs(cpu));
}

// The equal-area map's 1/√(1 + z) amplifies the rounding of z by 1/(1 + z)
// toward the antipode, in GLSL and C++ alike: mode 0's outputs p and q allow
// for it (w as shading_core_case makes it).
float condition_of(int mode, int output, const Vec4& a) {
    if (mode != 0 || output > 3) return 1.0f;
    const Vec3 w = glm::normalize(Vec3(a) + Vec3(0.0f, 0.0f, 1e-3f));
    return std::max(1.0f, 0.01f / std::max(1.0f + w.z, 1e-4f));
}

}  // namespace

TEST_CASE("every shading-core function gives the same results in GLSL as in C++", "[gl-core]") {
    test::gl_context();
    const GLuint vs = gl::compile_shader(GL_VERTEX_SHADER, gl::embedded_shader("fullscreen.vert.glsl"), "fullscreen.vert.glsl");
    const GLuint fs = gl::compile_shader(GL_FRAGMENT_SHADER, fragment_source(), "the shading-core test shader");
    gl::Program program(glCreateProgram());
    glAttachShader(program.id(), vs);
    glAttachShader(program.id(), fs);
    glLinkProgram(program.id());
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    REQUIRE(linked);
    glUseProgram(program.id());

    // The OVDF cube faces as the field and the GPU renderer set them up.
    Vec3 normals[6], s_axes[6], t_axes[6];
    for (int f = 0; f < 6; ++f) {
        normals[f] = CubeMap::face_direction(f, 0, 0);
        s_axes[f] = kSqrt2 * CubeMap::face_direction(f, 1, 0) - normals[f];
        t_axes[f] = kSqrt2 * CubeMap::face_direction(f, 0, 1) - normals[f];
    }
    glUniform3fv(glGetUniformLocation(program.id(), "u_normals"), 6, &normals[0].x);
    glUniform3fv(glGetUniformLocation(program.id(), "u_s"), 6, &s_axes[0].x);
    glUniform3fv(glGetUniformLocation(program.id(), "u_t"), 6, &t_axes[0].x);
    glUniform1i(glGetUniformLocation(program.id(), "u_a"), 0);
    glUniform1i(glGetUniformLocation(program.id(), "u_b"), 1);

    gl::Texture first = float_texture(nullptr), second = float_texture(nullptr);
    gl::Framebuffer framebuffer = gl::make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, first.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, second.id(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    REQUIRE(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    gl::VertexArray vao = gl::make_vertex_array();
    glBindVertexArray(vao.id());
    glViewport(0, 0, kSide, kSide);

    std::mt19937 rng(20061);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    size_t compared = 0;
    for (int mode = 0; mode < shading::kShadingCoreModes; ++mode) {
        std::vector<Vec4> a(kSide * kSide), b(kSide * kSide);
        for (size_t i = 0; i < a.size(); ++i) {
            a[i] = test::random_vec4(uniform, rng);
            b[i] = test::random_vec4(uniform, rng);
        }
        gl::Texture ta = float_texture(&a), tb = float_texture(&b);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, ta.id());
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, tb.id());
        glUniform1i(glGetUniformLocation(program.id(), "u_mode"), mode);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        std::vector<Vec4> gpu_first(a.size()), gpu_second(a.size());
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glReadPixels(0, 0, kSide, kSide, GL_RGBA, GL_FLOAT, gpu_first.data());
        glReadBuffer(GL_COLOR_ATTACHMENT1);
        glReadPixels(0, 0, kSide, kSide, GL_RGBA, GL_FLOAT, gpu_second.data());
        gl::check_gl("the shading-core test pass");

        int mismatches = 0;
        for (size_t i = 0; i < a.size(); ++i) {
            const shading::CaseOutput cpu = shading::shading_core_case(mode, a[i], b[i], normals, s_axes, t_axes);
            for (int c = 0; c < 8; ++c) {
                const float g = c < 4 ? gpu_first[i][c] : gpu_second[i][c - 4];
                const float e = c < 4 ? cpu.first[c] : cpu.second[c - 4];
                ++compared;
                if (close(g, e, condition_of(mode, c, a[i]))) continue;
                if (++mismatches <= 10)
                    UNSCOPED_INFO("mode " << mode << " case " << i << " output " << c << ": glsl " << g << ", c++ " << e
                                          << " (a = " << a[i].x << ' ' << a[i].y << ' ' << a[i].z << ' ' << a[i].w
                                          << ", b = " << b[i].x << ' ' << b[i].y << ' ' << b[i].z << ' ' << b[i].w << ')');
            }
        }
        CHECK(mismatches == 0);
    }
    CHECK(compared == size_t(shading::kShadingCoreModes) * kSide * kSide * 8);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace rsl
