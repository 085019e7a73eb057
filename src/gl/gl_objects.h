#pragma once
// Move-only owners of OpenGL objects, and the few helpers every pass uses:
// shader programs built from embedded sources, and flat arrays stored in 2D
// textures (2D textures are the one kind every driver sizes generously).
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "src/core/math.h"
#include "src/gl/gl.h"
#include "src/gl/gpu_layout.h"

namespace rsl::gl {

// A GL object name with its delete function.
template <void (*Delete)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    ~Handle() { reset(); }
    void reset() {
        if (id_) Delete(id_);
        id_ = 0;
    }
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }

private:
    GLuint id_ = 0;
};

void delete_texture(GLuint id);
void delete_buffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_framebuffer(GLuint id);
void delete_renderbuffer(GLuint id);
void delete_program(GLuint id);
void delete_query(GLuint id);
using Texture = Handle<delete_texture>;
using Buffer = Handle<delete_buffer>;
using VertexArray = Handle<delete_vertex_array>;
using Framebuffer = Handle<delete_framebuffer>;
using Renderbuffer = Handle<delete_renderbuffer>;
using Program = Handle<delete_program>;
using Query = Handle<delete_query>;

Texture make_texture();
Buffer make_buffer();
VertexArray make_vertex_array();
Framebuffer make_framebuffer();
Renderbuffer make_renderbuffer();
Query make_query();

// Compiles one shader from `source`; throws rsl::Error with the driver's log,
// naming `label` (the shader file, or what the source is).
GLuint compile_shader(GLenum type, const std::string& source, const std::string& label);

// Called by compile_shader with every source it hands the driver (stage,
// label, the whole text), so that a test can give the very same text to
// another compiler (tests/gl/shader_reference_test.cpp).
using ShaderSourceObserver = std::function<void(GLenum type, const std::string& label, const std::string& source)>;
// Sets this thread's observer (an empty one: none); returns the one it replaces.
ShaderSourceObserver observe_shader_sources(ShaderSourceObserver observer);

// Links the compiled `shaders` (deleted here) into a program; throws
// rsl::Error with the driver's log, naming `label`.
Program link_program(std::initializer_list<GLuint> shaders, const std::string& label);

// Compiles and links the embedded shaders/<vertex> and shaders/<fragment>;
// `defines` (e.g. "#define MAX_PARTS 32\n") go right after the #version line.
// Throws rsl::Error with the driver's log, naming the shader file.
Program build_program(const std::string& vertex, const std::string& fragment, const std::string& defines = "");
// The same with each stage's own defines.
Program build_program(const std::string& vertex, const std::string& fragment, const std::string& vertex_defines,
                      const std::string& fragment_defines);

// Compiles and links the embedded compute shader shaders/<compute>, `defines`
// after its #version line; throws rsl::Error with the driver's log.
Program build_compute_program(const std::string& compute, const std::string& defines = "");

// Throws rsl::Error naming `what`, the version needed and the current
// context's (context_description) when the context is older than major.minor.
void require_gl_version(int major, int minor, const std::string& what);

// What the shading pass gets before its own text: the layout constants
// (gpu_layout.h shader_layout_constants) and the shading core's GLSL part
// (src/shading/shading_core.h, embedded as "shading_core.glsl"); then a
// #line so that the driver's messages give the shader's own line numbers.
std::string shading_prelude();
// What the viewer's display passes get before their text: the sRGB curve
// (shaders/srgb.glsl), then a #line for the shader's own line numbers.
std::string srgb_prelude();
// What the shading passes read, after shading_prelude(): the samplers
// (gpu_interface.h kShadingSamplers), shaders/shading_data.glsl (the data
// and the BRDF average), visibility_fields.glsl (SVDF, OVDF, exact shapes)
// and shadow_map_filter.glsl (the shadow-map baseline). The sum itself
// (point_sum.glsl) comes after them (and after the GPU rays' text, with
// RAY_TRACED): the order of gpu_interface.h ShaderSource.
std::string shading_inputs_prelude();
// The file of `source` (gpu_interface.h kShaderSourceFiles) to go before a
// shader's own text, as that source string (#line 1 source), so that the
// driver's messages name its lines.
std::string included_shader(ShaderSource source);

// A flat array of vec4 (or half4) stored row-major in a 2D texture of fixed
// width: element i is texel (i % width, i / width). Shaders read it with
// texelFetch(tex, ivec2(i % width, i / width), 0).
struct ArrayTexture {
    Texture texture;
    int width = 1, height = 1;
    size_t size = 0;
    bool defined = false;  // upload_uint_array: storage allocated at this height
};
// Width used for every array texture: kArrayTextureWidth (gpu_layout.h).
// `internal_format`: GL_RGBA32F, or GL_RGBA16F for data that is exactly
// representable in half precision (the driver converts from float).
ArrayTexture make_array_texture(const std::vector<Vec4>& data, GLenum internal_format = GL_RGBA32F);
void update_array_texture(ArrayTexture& array, const std::vector<Vec4>& data);
// The same layout for uint data (GL_R32UI, read with a usampler2D), created
// on first use and re-allocated only when its row count changes.
void upload_uint_array(ArrayTexture& array, const std::vector<uint32_t>& data);

}  // namespace rsl::gl
