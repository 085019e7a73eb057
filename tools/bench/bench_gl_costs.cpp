// `rsl bench gl-costs`: what a compute shader's reads and branches cost on
// this GL device, per invocation, which decides how the vertex pass is written
// (docs/design/GPU_DESIGN.md, "What a software rasterizer pays"):
//  - a vec4 read by integer index from an RGBA32F texture (texelFetch), a
//    storage buffer and a uniform block, at random in a set that fits a
//    core's cache (16 KB) and in one that does not (16 MB);
//  - 64 reads in a row, the same under an `if` that no invocation takes,
//    in a loop of no turns, and as a loop of 64 turns of one read.
// On llvmpipe the `if` and the empty loop cost what the reads cost: a
// software rasterizer runs what it cannot jump over.
#ifdef RSL_HAVE_GL
#include <algorithm>
#include <chrono>
#include <vector>

#include <fmt/format.h>

#include "src/gl/gl_objects.h"
#include "src/gl/headless_context.h"
#include "tools/bench/bench.h"

namespace rsl::bench {
namespace {
using Clock = std::chrono::steady_clock;

constexpr int kWorkgroup = 64;
constexpr int kInvocations = 1 << 20;
constexpr int kReads = 64;  // per invocation
constexpr int kLargeSet = 1 << 20, kSmallSet = 1 << 10;  // vec4s: 16 MB, 16 KB (the least uniform block)
constexpr int kTextureWidth = 4096;

enum class Source { Texture, StorageBuffer, UniformBlock };
enum class Shape { Straight, UntakenIf, EmptyLoop, LoopOfReads };

const char* kShader = R"(
layout(local_size_x = WORKGROUP) in;
layout(std430, binding = 0) readonly buffer Data { vec4 data[]; };
layout(std430, binding = 1) writeonly buffer Sums { vec4 sums[]; };
layout(std140, binding = 0) uniform Block { vec4 block[SMALL_SET]; };
uniform sampler2D u_texels;
uniform uint u_mask;  // the set's size - 1
uniform int u_zero;   // 0, which the compiler cannot know

vec4 read_at(uint i) {
#if SOURCE == 0
    return texelFetch(u_texels, ivec2(int(i % uint(TEXTURE_WIDTH)), int(i / uint(TEXTURE_WIDTH))), 0);
#elif SOURCE == 1
    return data[i];
#else
    return block[i];
#endif
}
#define READ h = h * 1664525u + 1013904223u; sum += read_at((h >> 8) & u_mask);
#define READ8 READ READ READ READ READ READ READ READ
#define READ64 READ8 READ8 READ8 READ8 READ8 READ8 READ8 READ8

void main() {
    uint h = gl_GlobalInvocationID.x * 2654435761u;
    vec4 sum = vec4(0.0);
#if SHAPE == 0
    READ64
#elif SHAPE == 1
    if (u_zero != 0) { READ64 }
#elif SHAPE == 2
    for (int k = 0; k < u_zero; ++k) { READ64 }
#else
    for (int k = 0; k < 64 + u_zero; ++k) { READ }
#endif
    sums[gl_GlobalInvocationID.x] = sum;
}
)";

gl::Program cost_program(Source source, Shape shape) {
    const std::string text = fmt::format(
        "#version 430 core\n#define WORKGROUP {}\n#define SMALL_SET {}\n#define TEXTURE_WIDTH {}\n#define SOURCE {}\n"
        "#define SHAPE {}\n{}",
        kWorkgroup, kSmallSet, kTextureWidth, int(source), int(shape), kShader);
    return gl::link_program({gl::compile_shader(GL_COMPUTE_SHADER, text, "the gl-costs shader")}, "the gl-costs shader");
}

// Milliseconds per dispatch of every invocation: dispatches repeated to at
// least 50 ms between two glFinish, the least of three such runs.
double dispatch_ms(const gl::Program& program, int set) {
    glUseProgram(program.id());
    glUniform1i(glGetUniformLocation(program.id(), "u_texels"), 0);
    glUniform1ui(glGetUniformLocation(program.id(), "u_mask"), GLuint(set - 1));
    glUniform1i(glGetUniformLocation(program.id(), "u_zero"), 0);
    auto run = [](int repeats) {
        glFinish();
        const auto start = Clock::now();
        for (int r = 0; r < repeats; ++r) glDispatchCompute(kInvocations / kWorkgroup, 1, 1);
        glFinish();
        return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    };
    const double once = run(1);  // also the warm-up: some drivers compile at first use
    const int repeats = std::clamp(int(50.0 / std::max(once, 1e-3)), 1, 1000);
    double least = 1e30;
    for (int trial = 0; trial < 3; ++trial) least = std::min(least, run(repeats) / repeats);
    gl::check_gl("the gl-costs dispatch");
    return least;
}

RegisterBenchmark gl_costs_benchmark(
    {"gl-costs", "GL device: cost per invocation of a vec4 read (texture, storage buffer, uniform block) and of "
                 "branches no invocation takes",
     [](const BenchOptions&) {
         gl::HeadlessContext context;
         const std::string device = context.description();
         std::vector<Vec4> values(kLargeSet);
         for (size_t i = 0; i < values.size(); ++i) values[i] = Vec4(float(i % 7), 1.0f, 0.5f, 0.25f);
         gl::Texture texture = gl::make_texture();
         glActiveTexture(GL_TEXTURE0);
         glBindTexture(GL_TEXTURE_2D, texture.id());
         glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTextureWidth, kLargeSet / kTextureWidth, 0, GL_RGBA, GL_FLOAT,
                      values.data());
         glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
         glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
         gl::Buffer data = gl::make_buffer(), sums = gl::make_buffer(), block = gl::make_buffer();
         glBindBuffer(GL_SHADER_STORAGE_BUFFER, data.id());
         glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(values.size() * sizeof(Vec4)), values.data(), GL_STATIC_DRAW);
         glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data.id());
         glBindBuffer(GL_SHADER_STORAGE_BUFFER, sums.id());
         glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(kInvocations * sizeof(Vec4)), nullptr, GL_DYNAMIC_COPY);
         glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums.id());
         glBindBuffer(GL_UNIFORM_BUFFER, block.id());
         glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(kSmallSet * sizeof(Vec4)), values.data(), GL_STATIC_DRAW);
         glBindBufferBase(GL_UNIFORM_BUFFER, 0, block.id());
         gl::check_gl("the gl-costs data");

         const double reads = double(kInvocations) * kReads;
         struct ReadCase {
             Source source;
             const char* name;
             int set;
         };
         double texture_small_ns = 0;
         for (const ReadCase& c : {ReadCase{Source::Texture, "texture (texelFetch)", kSmallSet},
                                   ReadCase{Source::StorageBuffer, "storage buffer", kSmallSet},
                                   ReadCase{Source::UniformBlock, "uniform block", kSmallSet},
                                   ReadCase{Source::Texture, "texture (texelFetch)", kLargeSet},
                                   ReadCase{Source::StorageBuffer, "storage buffer", kLargeSet}}) {
             const double ns = 1e6 * dispatch_ms(cost_program(c.source, Shape::Straight), c.set) / reads;
             if (c.source == Source::Texture && c.set == kSmallSet) texture_small_ns = ns;
             bench_emit({{"bench", "gl-costs"},
                         {"case", fmt::format("vec4 read from a {}, random in {} KB", c.name, c.set * 16 / 1024)},
                         {"device", device},
                         {"invocations", kInvocations},
                         {"ns_per_invocation_read", ns},
                         {"relative_to_texture_16kb", ns / texture_small_ns}});
         }
         const double straight = dispatch_ms(cost_program(Source::Texture, Shape::Straight), kSmallSet);
         struct ShapeCase {
             Shape shape;
             const char* name;
         };
         for (const ShapeCase& c : {ShapeCase{Shape::Straight, "64 texture reads in a row"},
                                    ShapeCase{Shape::UntakenIf, "the 64 reads under an if no invocation takes"},
                                    ShapeCase{Shape::EmptyLoop, "the 64 reads in a loop of no turns"},
                                    ShapeCase{Shape::LoopOfReads, "a loop of 64 turns, one read each"}}) {
             const double ms = c.shape == Shape::Straight ? straight
                                                          : dispatch_ms(cost_program(Source::Texture, c.shape), kSmallSet);
             bench_emit({{"bench", "gl-costs"},
                         {"case", c.name},
                         {"device", device},
                         {"invocations", kInvocations},
                         {"ms", ms},
                         {"relative_to_reads_in_a_row", ms / straight}});
         }
     }});

}  // namespace
}  // namespace rsl::bench
#endif  // RSL_HAVE_GL
