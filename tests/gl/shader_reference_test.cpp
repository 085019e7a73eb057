// Every shader the GL renderer compiles, as the driver gets it, through the
// Khronos reference compiler (glslangValidator, Debian's glslang-tools).
// Mesa's compiler is the only one the suite runs; the reference front end
// holds the text to the GLSL 4.30 specification, so a construct that Mesa
// lets through and another vendor's driver would refuse fails here, without
// that vendor's GPU (docs/GPU.md "Running on an NVIDIA GPU server").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "src/gl/gl_objects.h"
#include "src/gl/gl_renderer.h"
#include "src/gl/gpu_bvh.h"
#include "tools/viewer/skybox.h"
#include "src/render/part_fields.h"
#include "tests/gl/gl_test_support.h"
#include "tests/render/render_test_scenes.h"

namespace rsl {
namespace {

namespace fs = std::filesystem;

struct CapturedShader {
    GLenum type = 0;
    std::string label, source;
};

// glslangValidator's stage name for a GL shader type.
std::string stage_name(GLenum type) {
    switch (type) {
    case GL_VERTEX_SHADER: return "vert";
    case GL_FRAGMENT_SHADER: return "frag";
    case GL_COMPUTE_SHADER: return "comp";
    default: return "unknown";
    }
}

// Runs `command`, returns its exit status and what it printed (stdout and stderr).
int run_command(const std::string& command, std::string& output) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    REQUIRE(pipe != nullptr);
    char buffer[4096];
    size_t n = 0;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
    const int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The shaders compile_shader hands the driver while `work` runs, each text once.
template <class Work>
std::vector<CapturedShader> capture_shaders(Work&& work) {
    std::vector<CapturedShader> captured;
    std::set<std::string> seen;
    const gl::ShaderSourceObserver previous =
        gl::observe_shader_sources([&](GLenum type, const std::string& label, const std::string& source) {
            if (seen.insert(source).second) captured.push_back({type, label, source});
        });
    try {
        work();
    } catch (...) {
        gl::observe_shader_sources(previous);
        throw;
    }
    gl::observe_shader_sources(previous);
    return captured;
}

// The per-pixel shadow scene with a textured ground (a layered part), a
// sphere light, and 40 environment RSLs (two light words): every define of
// the vertex pass is on in one of the runs below.
Scene reference_scene() {
    Scene scene = test::box_over_coarse_ground(true);
    LocalLight light;
    light.radius = 0.05f;
    light.power = Color(2.0f);
    light.position = Vec3(-0.5f, 1.5f, 0.5f);
    scene.lights.push_back(light);
    return scene;
}

TEST_CASE("every shader the GL renderer compiles passes the reference GLSL compiler", "[gl-core]") {
    std::string version;
    INFO("glslangValidator not found: install Debian's glslang-tools (scripts/quickstart.sh does)");
    REQUIRE(run_command("glslangValidator --version", version) == 0);
    test::gl_context();
    const Scene scene = reference_scene();
    const PartFields fields = bake_part_fields(scene, FieldBakeOptions{});
    const RslSet lights = test::random_rsls(40, 7);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, 0.0f, 64, 48);

    const std::vector<CapturedShader> shaders = capture_shaders([&] {
        // The plain pass (with the per-pixel pass and the block lists the
        // tests record), then each visibility baseline.
        for (int run = 0; run < 3; ++run) {
            RenderOptions options;
            options.shadow_maps.enabled = run == 1;
            options.gpu_rays.enabled = run == 2;
            gl::GlRenderer renderer(scene, lights, fields, options);
            renderer.keep_image_terms(true);
            renderer.set_time(0.0f);
            const VertexColors colors = renderer.shade();
            renderer.form_image(colors, camera);
            if (run == 0) renderer.block_candidate_lights();
        }
        // The viewer's sky, and the GPU rays of `rsl truth`.
        const CubeMap sky = test::sky_with_sun(4);
        gl::Skybox skybox(sky, &sky);
        gl::GpuBvh bvh(scene);
        std::vector<Mat4> poses;
        for (const Part& part : scene.parts) poses.push_back(scene.nodes[part.node].rest.matrix());
        bvh.set_poses(poses);
        bvh.occluded({Vec3(0.0f, 2.0f, 0.0f)}, {Vec3(0.0f, -1.0f, 0.0f)}, 10.0f);
    });

    // Each variant the renderer builds was seen (a define left out of the
    // capture would leave its code unchecked).
    for (const char* define : {"#define LAYERED 1", "#define LOCAL_LIGHTS 1", "#define RAY_TRACED 1",
                               "#define SHADOW_MAPPED 1", "#define RECORD_BLOCK_LIGHTS 1", "#define LIGHT_WORDS 2"}) {
        INFO(define);
        CHECK(std::any_of(shaders.begin(), shaders.end(), [&](const CapturedShader& shader) {
            return shader.source.find(define) != std::string::npos;
        }));
    }
    std::set<std::string> stages;
    for (const CapturedShader& shader : shaders) stages.insert(stage_name(shader.type));
    CHECK(stages == std::set<std::string>{"comp", "frag", "vert"});

    const fs::path folder = fs::temp_directory_path() / ("rsl-shader-reference-" + std::to_string(::getpid()));
    fs::create_directories(folder);
    int index = 0;
    // Without -V: OpenGL semantics, the #version line's profile. Returns the exit status.
    auto validate = [&](GLenum type, const std::string& source, std::string& log) {
        const fs::path file = folder / (std::to_string(index++) + "." + stage_name(type));
        std::ofstream(file) << source;
        return run_command("glslangValidator " + file.string(), log);
    };
    for (const CapturedShader& shader : shaders) {
        std::string log;
        const int status = validate(shader.type, shader.source, log);
        INFO(shader.label << ":\n" << log);
        CHECK(status == 0);
    }
    // The check can fail: a text the specification refuses (a vec3 into a float).
    std::string log;
    CHECK(validate(GL_COMPUTE_SHADER, "#version 430 core\nlayout(local_size_x = 1) in;\n"
                                      "void main() { float x = vec3(1.0); }\n", log) != 0);
    CHECK_THAT(log, Catch::Contains("ERROR"));
    fs::remove_all(folder);
    CHECK(shaders.size() >= 10);
}

}  // namespace
}  // namespace rsl
