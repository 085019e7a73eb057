#include "src/gl/gl_objects.h"

#include <algorithm>
#include <initializer_list>

#include "src/core/error.h"
#include "src/gl/shader_sources.h"

namespace rsl::gl {

void check_gl(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) throw Error(fmt::format("OpenGL error 0x{:04x} in {}", unsigned(error), what));
}

std::string context_description() {
    auto text = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return "OpenGL " + text(GL_VERSION) + " on " + text(GL_RENDERER);
}

bool is_software_renderer() {
    const GLubyte* name = glGetString(GL_RENDERER);
    if (!name) return false;
    const std::string renderer(reinterpret_cast<const char*>(name));
    for (const char* software : {"llvmpipe", "softpipe", "swrast"})
        if (renderer.find(software) != std::string::npos) return true;
    return false;
}

bool has_current_context() { return glGetString(GL_VERSION) != nullptr; }

void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_query(GLuint id) { glDeleteQueries(1, &id); }

namespace {

// A fresh object's name from one of GL's glGen* calls.
GLuint generated(void (*generate)(GLsizei, GLuint*)) {
    GLuint id = 0;
    generate(1, &id);
    return id;
}

}  // namespace

Texture make_texture() { return Texture(generated(glGenTextures)); }
Buffer make_buffer() { return Buffer(generated(glGenBuffers)); }
VertexArray make_vertex_array() { return VertexArray(generated(glGenVertexArrays)); }
Framebuffer make_framebuffer() { return Framebuffer(generated(glGenFramebuffers)); }
Renderbuffer make_renderbuffer() { return Renderbuffer(generated(glGenRenderbuffers)); }
Query make_query() { return Query(generated(glGenQueries)); }

namespace {

std::string shader_text(const std::string& name) {
    const char* source = embedded_shader(name);
    if (!source) throw Error(fmt::format("shaders/{}: no such embedded shader", name));
    return source;
}

// The #version line stays first; defines follow it.
std::string with_defines(const std::string& source, const std::string& defines) {
    if (defines.empty()) return source;
    const size_t version = source.find("#version");
    if (version == std::string::npos) return defines + source;
    const size_t eol = source.find('\n', version);
    return source.substr(0, eol + 1) + defines + source.substr(eol + 1);
}

GLuint compile(GLenum type, const std::string& name, const std::string& defines) {
    return compile_shader(type, with_defines(shader_text(name), defines), "shaders/" + name);
}

thread_local ShaderSourceObserver shader_source_observer;

}  // namespace

ShaderSourceObserver observe_shader_sources(ShaderSourceObserver observer) {
    return std::exchange(shader_source_observer, std::move(observer));
}

GLuint compile_shader(GLenum type, const std::string& source, const std::string& label) {
    if (shader_source_observer) shader_source_observer(type, label, source);
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw Error(fmt::format("{}: compilation failed:\n{}", label, log));
    }
    return shader;
}

std::string shading_prelude() {
    return shader_layout_constants() + "#define RSL_SHARED\n#define RSL_CONST const\n" +
           included_shader(kSourceShadingCore);
}

std::string srgb_prelude() { return included_shader(kSourceSrgb); }

std::string shading_inputs_prelude() {
    return shader_sampler_declarations() + included_shader(kSourceShadingData) +
           included_shader(kSourceVisibilityFields) + included_shader(kSourceShadowMapFilter);
}

std::string included_shader(ShaderSource source) {
    RSL_CHECK(source > kSourcePass && source < kSourceCount);
    return fmt::format("#line 1 {}\n", int(source)) + shader_text(kShaderSourceFiles[source]) + "#line 2 0\n";
}

Program build_program(const std::string& vertex, const std::string& fragment, const std::string& defines) {
    return build_program(vertex, fragment, defines, defines);
}

Program build_program(const std::string& vertex, const std::string& fragment, const std::string& vertex_defines,
                      const std::string& fragment_defines) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex, vertex_defines);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment, fragment_defines);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    return link_program({vs, fs}, fmt::format("shaders/{} + shaders/{}", vertex, fragment));
}

Program link_program(std::initializer_list<GLuint> shaders, const std::string& label) {
    Program program(glCreateProgram());
    for (const GLuint shader : shaders) glAttachShader(program.id(), shader);
    glLinkProgram(program.id());
    for (const GLuint shader : shaders) glDeleteShader(shader);
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.id(), length, nullptr, log.data());
        throw Error(fmt::format("{}: link failed:\n{}", label, log));
    }
    return program;
}

Program build_compute_program(const std::string& compute, const std::string& defines) {
    return link_program({compile(GL_COMPUTE_SHADER, compute, defines)}, "shaders/" + compute);
}

void require_gl_version(int major, int minor, const std::string& what) {
    GLint have_major = 0, have_minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &have_major);
    glGetIntegerv(GL_MINOR_VERSION, &have_minor);
    if (have_major > major || (have_major == major && have_minor >= minor)) return;
    throw Error(fmt::format("{} needs OpenGL {}.{} or newer (compute shaders and storage buffers); the current "
                            "context is {}",
                            what, major, minor, context_description()));
}

namespace {

// Sizes `array` for `texels` elements; throws when the driver's largest
// texture cannot hold them.
void size_array(ArrayTexture& array, size_t texels) {
    array.size = texels;
    array.width = kArrayTextureWidth;
    array.height = int(std::max<size_t>(1, (texels + kArrayTextureWidth - 1) / kArrayTextureWidth));
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (array.height > max_size)
        throw Error(fmt::format("GPU data of {} texels needs a {}×{} texture; this driver allows {}", texels,
                                array.width, array.height, max_size));
}

void upload_array(ArrayTexture& array, const std::vector<Vec4>& data, GLenum internal_format) {
    size_array(array, data.size());
    // Pad the last row so that the upload reads only owned memory.
    std::vector<Vec4> padded;
    const Vec4* pixels = data.data();
    if (data.size() != size_t(array.width) * array.height) {
        padded = data;
        padded.resize(size_t(array.width) * array.height, Vec4(0.0f));
        pixels = padded.data();
    }
    glBindTexture(GL_TEXTURE_2D, array.texture.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), array.width, array.height, 0, GL_RGBA, GL_FLOAT, pixels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    check_gl("uploading an array texture");
}

}  // namespace

ArrayTexture make_array_texture(const std::vector<Vec4>& data, GLenum internal_format) {
    ArrayTexture array;
    array.texture = make_texture();
    upload_array(array, data, internal_format);
    return array;
}

void update_array_texture(ArrayTexture& array, const std::vector<Vec4>& data) {
    GLint format = GL_RGBA32F;
    glBindTexture(GL_TEXTURE_2D, array.texture.id());
    glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    const int height = int(std::max<size_t>(1, (data.size() + kArrayTextureWidth - 1) / kArrayTextureWidth));
    if (height != array.height) {
        upload_array(array, data, GLenum(format));
        return;
    }
    array.size = data.size();
    const int full_rows = int(data.size() / kArrayTextureWidth);
    if (full_rows > 0)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kArrayTextureWidth, full_rows, GL_RGBA, GL_FLOAT, data.data());
    const int rest = int(data.size() % kArrayTextureWidth);
    if (rest > 0)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, full_rows, rest, 1, GL_RGBA, GL_FLOAT,
                        data.data() + size_t(full_rows) * kArrayTextureWidth);
    check_gl("updating an array texture");
}

void upload_uint_array(ArrayTexture& array, const std::vector<uint32_t>& data) {
    if (!array.texture.id()) array.texture = make_texture();
    const int height = array.height;
    size_array(array, data.size());
    glBindTexture(GL_TEXTURE_2D, array.texture.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (height != array.height || !array.defined) {  // storage only; the rows follow
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, array.width, array.height, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        array.defined = true;
    }
    const int full_rows = int(data.size() / size_t(array.width));
    if (full_rows > 0)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, array.width, full_rows, GL_RED_INTEGER, GL_UNSIGNED_INT, data.data());
    const int rest = int(data.size() % size_t(array.width));
    if (rest > 0)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, full_rows, rest, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                        data.data() + size_t(full_rows) * size_t(array.width));
    check_gl("uploading a uint array texture");
}

}  // namespace rsl::gl
