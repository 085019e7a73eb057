// `rsl bench gl`: the GPU renderer (headless EGL context) on the robot,
// bunny, kitchen and yard scenes at 30 RSLs: the vertex pass against the CPU
// renderer on the same frames (time, occluder lookups, block culling,
// parity), frames per second of the vertex pass alone and of the full frame
// (plus the display pass into a 640×480 target, with and without the
// per-pixel pass), and why the BRDF tables are stored in 32-bit rather than
// 16-bit float.
#ifdef RSL_HAVE_GL
#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "src/fields/cpca.h"
#include "tools/bench/bench.h"
#include "src/formats/scene_file.h"
#include "src/gl/gl_renderer.h"
#include "src/gl/headless_context.h"
#include "tools/viewer/viewer.h"
#include "src/image/error_metrics.h"
#include "src/render/cpu_renderer.h"
#include "src/render/render_setup.h"
#include "tools/assets/yard.h"

namespace rsl::bench {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// An offscreen colour + depth target for the display pass.
struct DisplayTarget {
    gl::Framebuffer fbo = gl::make_framebuffer();
    gl::Renderbuffer color = gl::make_renderbuffer(), depth = gl::make_renderbuffer();
    DisplayTarget(int width, int height) {
        glBindRenderbuffer(GL_RENDERBUFFER, color.id());
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, depth.id());
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color.id());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
};

// The shading pass against the CPU renderer on the same frames, alternated
// in one run: per frame the CPU's shade() and the GPU's vertex pass (wall
// clock around glFinish), the occluder lookups each made, and the
// block-level culling. The least frame time of each (the noise on a shared
// machine only adds).
struct ShadingComparison {
    double cpu_ms = 1e30, gpu_ms = 1e30, gpu_pass_ms = 0;
    double cpu_lookups = 0, gpu_lookups = 0;  // per frame
    double cpu_block_culled = 0, gpu_block_pairs = 0, gpu_block_culled = 0;
    double parity = 0;  // relative L2 of the GPU's colours against the CPU's, last frame
};

ShadingComparison compare_shading(gl::GlRenderer& gpu, CpuRenderer& cpu, const std::vector<float>& times) {
    ShadingComparison c;
    VertexColors cpu_colors = cpu.make_output(), gpu_colors = gpu.make_output();
    for (const float t : times) {
        cpu.set_time(t);
        auto start = Clock::now();
        cpu.shade(cpu_colors);
        c.cpu_ms = std::min(c.cpu_ms, 1e3 * since(start));
        c.cpu_lookups += double(cpu.stats().occluder_lookups);
        c.cpu_block_culled += double(cpu.stats().block_occluders_culled);
        gpu.set_time(t);
        glFinish();
        start = Clock::now();
        gpu.shade_on_device();
        glFinish();
        c.gpu_ms = std::min(c.gpu_ms, 1e3 * since(start));
        const gl::DeviceCounts counts = gpu.device_counts();
        c.gpu_lookups += double(counts.occluder_lookups);
        c.gpu_block_pairs += double(counts.block_pairs);
        c.gpu_block_culled += double(counts.block_pairs_culled);
    }
    const double frames = double(times.size());
    c.cpu_lookups /= frames, c.gpu_lookups /= frames;
    c.cpu_block_culled /= frames, c.gpu_block_pairs /= frames, c.gpu_block_culled /= frames;
    gpu.shade(gpu_colors);  // the last frame again, read back
    c.parity = compare_vertex_colors(gpu_colors, cpu_colors).total.relative_l2();
    c.gpu_pass_ms = gpu.timings().shade_ms;  // timer queries: a recent frame's (the clock on software GL)
    return c;
}

// `full_frames`: also time the display pass (with and without the per-pixel
// pass); the yards measure the vertex pass alone (on llvmpipe a yard-128 frame
// with the per-pixel pass takes about 8 s).
void bench_scene(std::shared_ptr<Scene> scene, const std::string& name, const BenchOptions& options,
                 const std::string& device, bool full_frames) {
    // The paper's settings take minutes to bake; --quick benches small fields
    // (fewer PCA vectors: cheaper lookups, so faster than the full fields).
    if (options.quick) gl::use_quick_fields(scene->precompute);
    RenderOptions render;
    render.environment_light_count = 30;
    const RenderSetup setup = prepare_render(scene, render, {.progress = {}, .field_cache = options.field_cache});
    gl::GlRenderer renderer(*scene, setup.environment_lights, setup.fields, render);
    CpuRenderer cpu(*scene, setup.environment_lights, setup.fields, render);
    const int frames = options.quick ? 4 : 12;
    const float duration = std::max(scene->animation.end - scene->animation.start, 1e-3f);
    auto time_of = [&](int f) { return scene->animation.start + duration * float(f) / float(frames); };

    renderer.set_time(time_of(0));
    renderer.shade_on_device();  // warm-up: shader compilation happens at first use on some drivers
    glFinish();
    std::vector<float> compared_times;
    for (int f = 0; f < (options.quick ? 2 : 4); ++f) compared_times.push_back(time_of(f * frames / 4 + frames / 8));
    const ShadingComparison compared = compare_shading(renderer, cpu, compared_times);
    auto start = Clock::now();
    for (int f = 0; f < frames; ++f) {
        renderer.set_time(time_of(f));
        renderer.shade_on_device();
    }
    glFinish();
    const double shade_seconds = since(start) / frames;

    // Full frames: the shading pass, then the display pass into a 640×480
    // target, with the per-pixel pass (the default: grounds and glossy parts
    // shaded per pixel, docs/design/GPU_DESIGN.md) and without it (every part the vertex
    // colours' blend). Fewer frames: on a software rasterizer a frame with
    // the per-pixel pass takes tens of seconds.
    const int width = 640, height = 480;
    DisplayTarget target(width, height);
    const Camera& camera = scene->camera;
    const int display_frames = options.quick ? 1 : 4;
    auto time_frames = [&](bool per_pixel) {
        RenderOptions toggles = render;
        if (!per_pixel) toggles.pixel_shadows = PixelShadows::Off, toggles.pixel_highlights = false;
        renderer.set_toggles(toggles);
        const auto begin = Clock::now();
        for (int f = 0; f < display_frames; ++f) {
            const float t = time_of(f * frames / display_frames);
            renderer.set_time(t);
            renderer.shade_on_device();
            glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.id());
            glViewport(0, 0, width, height);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            const Mat4 view_projection =
                glm::perspective(glm::radians(camera.fov_y_degrees), float(width) / height, 0.05f, 100.0f) *
                glm::lookAt(camera.position_at(t), camera.target_at(t), camera.up);
            renderer.draw(view_projection, 1.0f);
        }
        glFinish();
        return since(begin) / display_frames;
    };
    const double blend_frame_seconds = full_frames ? time_frames(false) : 0.0;
    const double frame_seconds = full_frames ? time_frames(true) : 0.0;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    bench_emit({{"bench", "gl"},
                {"case", name + " 30 RSLs"},
                {"device", device},
                {"quick_fields", options.quick},
                {"vertices", renderer.vertex_count()},
                {"lights", renderer.stats().lights},
                {"frames", frames},
                {"shading_ms", 1e3 * shade_seconds},
                {"shading_fps", 1.0 / shade_seconds},
                {"compared_frames", compared_times.size()},
                {"cpu_shading_ms", compared.cpu_ms},
                {"gpu_shading_ms", compared.gpu_ms},
                {"gpu_pass_ms", compared.gpu_pass_ms},
                {"gpu_over_cpu", compared.gpu_ms / compared.cpu_ms},
                {"cpu_occluder_lookups", compared.cpu_lookups},
                {"gpu_occluder_lookups", compared.gpu_lookups},
                {"gpu_over_cpu_lookups", compared.cpu_lookups > 0 ? compared.gpu_lookups / compared.cpu_lookups : 1.0},
                {"cpu_block_occluders_culled", compared.cpu_block_culled},
                {"gpu_block_pairs", compared.gpu_block_pairs},
                {"gpu_block_pairs_culled", compared.gpu_block_culled},
                {"gpu_cpu_relative_l2", compared.parity},
                {"display_frames", full_frames ? display_frames : 0},
                {"frame_ms", full_frames ? nlohmann::json(1e3 * frame_seconds) : nlohmann::json()},
                {"frame_fps", full_frames ? nlohmann::json(1.0 / frame_seconds) : nlohmann::json()},
                {"frame_vertex_blend_ms", full_frames ? nlohmann::json(1e3 * blend_frame_seconds) : nlohmann::json()},
                {"frame_vertex_blend_fps", full_frames ? nlohmann::json(1.0 / blend_frame_seconds) : nlohmann::json()},
                {"occluder_pairs", renderer.stats().occluder_pairs},
                {"occluder_pairs_culled", renderer.stats().occluder_pairs_culled},
                {"gpu_megabytes", double(renderer.gpu_bytes()) / (1 << 20)}});
}

// One-texel squares read from the SAT (four corner taps), against the
// tabulated texel: the relative error of float storage and of half storage.
void bench_sat_precision(const fs::path& path) {
    if (!fs::exists(path)) return;
    const Scene scene = load_scene(path);
    for (const MaterialDesc& material : scene.materials) {
        const auto table = BrdfTable::build(*make_brdf(material));
        const int n = table->grid().n, stride = n + 1;
        const std::vector<float>& entries = table->lookup_data();
        std::vector<double> float_errors, half_errors;
        for (int s = 0; s < table->slice_count(); ++s)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const Color texel = table->texel(s, i, j);
                    for (int c = 0; c < 3; ++c) {
                        if (!(texel[c] > 1e-3f * table->offset(s)[c])) continue;  // below the horizon / negligible
                        auto corner = [&](int a, int b, bool half) {
                            const float v = entries[((size_t(2 * s) * stride + b) * stride + a) * 3 + c];  // layer 0: corner sums
                            return double(half ? round_to_half(v) : v);
                        };
                        for (const bool half : {false, true}) {
                            const double integral = corner(i + 1, j + 1, half) - corner(i, j + 1, half) -
                                                    corner(i + 1, j, half) + corner(i, j, half) +
                                                    double(table->offset(s)[c]);  // offset·(area 1)
                            const double error = std::abs(integral - texel[c]) / texel[c];
                            (half ? half_errors : float_errors).push_back(error);
                        }
                    }
                }
        auto percentile = [](std::vector<double>& v, double q) {
            if (v.empty()) return 0.0;
            const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
            std::nth_element(v.begin(), v.begin() + k, v.end());
            return v[k];
        };
        bench_emit({{"bench", "gl"},
                    {"case", "BRDF SAT storage " + material.name + " (" + material.model + ")"},
                    {"texel_values", float_errors.size()},
                    {"float32_median_relative_error", percentile(float_errors, 0.5)},
                    {"float32_p99_relative_error", percentile(float_errors, 0.99)},
                    {"float16_median_relative_error", percentile(half_errors, 0.5)},
                    {"float16_p99_relative_error", percentile(half_errors, 0.99)}});
    }
}

RegisterBenchmark gl_benchmark({"gl", "GPU renderer against the CPU on robot, bunny, kitchen and yards (--parts): "
                                      "shading time, occluder lookups, block culling, parity; full-frame fps; SAT precision",
    [](const BenchOptions& options) {
        gl::HeadlessContext context;
        const std::string device = context.description();
        const fs::path& scenes = options.scenes;
        bench_sat_precision(scenes / "robot.json");
        for (const char* name : {"robot", "bunny", "kitchen"}) {
            const fs::path path = scenes / (std::string(name) + ".json");
            if (!fs::exists(path)) {
                bench_emit({{"bench", "gl"}, {"case", name}, {"skipped", "missing " + path.string()}});
                continue;
            }
            bench_scene(std::make_shared<Scene>(load_scene(path)), name, options, device, true);
        }
        // The yards (tools/assets/yard.h): many moving parts on a ground; --parts picks their sizes.
        std::vector<int> yards = options.scale_parts;
        if (yards.empty()) yards = {options.quick ? 8 : 128};
        for (const int n : yards) {
            const fs::path dir = options.output / "gl" / fmt::format("yard-{}", n);
            fs::create_directories(dir);
            const fs::path environment = fs::absolute(options.generated_assets / "sunsky.exr");
            const fs::path file = assets::write_yard(dir, n, environment.string());
            bench_scene(std::make_shared<Scene>(load_scene(file)), fmt::format("yard-{}", n), options, device, false);
        }
    }});

}  // namespace
}  // namespace rsl::bench
#endif  // RSL_HAVE_GL
