// The viewer's window, input and frame loop (panel: viewer_panel.cpp).
#define GLFW_INCLUDE_NONE
#include "tools/viewer/viewer.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "src/formats/scene_file.h"
#include "src/gl/gl.h"
#include "tools/viewer/skybox.h"
#include "tools/viewer/viewer_state.h"
#include "src/render/render_setup.h"

namespace rsl::gl {

void use_quick_fields(PrecomputeSettings& pre) {
    pre.svdf_resolution = 16, pre.svdf_clusters = 32, pre.svdf_vectors = 4, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 6, pre.ovdf_cube_resolution = 8, pre.ovdf_vdt_resolution = 16, pre.ovdf_vectors = 4;
}

namespace {

// glfwInit / glfwTerminate and the window, released in reverse order.
struct Window {
    GLFWwindow* window = nullptr;
    Window(int width, int height, const std::string& title) {
        glfwSetErrorCallback([](int code, const char* message) { std::fprintf(stderr, "GLFW %d: %s\n", code, message); });
        if (!glfwInit()) throw Error("rsl view: GLFW could not start (no display? try xvfb-run -a rsl view ...)");
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
        if (!window) {
            glfwTerminate();
            throw Error("rsl view: no window with an OpenGL 4.3 core context");
        }
        glfwMakeContextCurrent(window);
        glfwSwapInterval(0);  // measure the renderer, not the display's refresh
    }
    ~Window() {
        glfwDestroyWindow(window);
        glfwTerminate();
    }
};

struct ImGuiSession {
    explicit ImGuiSession(GLFWwindow* window) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
        ImGui::StyleColorsDark();
        ImGui_ImplGlfw_InitForOpenGL(window, true);
        ImGui_ImplOpenGL3_Init("#version 330 core");
    }
    ~ImGuiSession() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
};

// Mouse and keys that ImGui does not take.
struct Input {
    double last_x = 0, last_y = 0;
    bool space_down = false, h_down = false, r_down = false;
};

void handle_input(GLFWwindow* window, Input& input, ViewerState& state, float dt) {
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    const float dx = float(x - input.last_x), dy = float(y - input.last_y);
    input.last_x = x, input.last_y = y;
    if (ImGui::GetIO().WantCaptureMouse) return;
    const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        if (shift && !state.scene->lights.empty()) {
            // Move the light in the view plane, scaled to the orbit distance.
            LocalLight& light = state.scene->lights.front();
            const Vec3 forward = glm::normalize(state.camera.target - state.camera.eye());
            const Vec3 right = glm::normalize(glm::cross(forward, Vec3(0, 1, 0)));
            const Vec3 up = glm::cross(right, forward);
            const float scale = 0.002f * state.camera.distance;
            light.position += scale * (dx * right - dy * up);
            light.path.reset();
            light.node = -1;  // a glTF light leaves its node (position and axis hold its pose at the start)
            state.lights_dirty = true;
        } else {
            state.camera.yaw -= 0.005f * dx;
            state.camera.pitch = std::clamp(state.camera.pitch + 0.005f * dy, -1.5f, 1.5f);
        }
    }
    if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) state.environment_degrees += 0.3f * dx;
    // The wheel zooms (ImGui's GLFW backend collects the scroll events).
    state.camera.distance *= std::pow(0.9f, ImGui::GetIO().MouseWheel);
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    if (glfwGetKey(window, GLFW_KEY_LEFT) == GLFW_PRESS) state.environment_degrees -= 60.0f * dt;
    if (glfwGetKey(window, GLFW_KEY_RIGHT) == GLFW_PRESS) state.environment_degrees += 60.0f * dt;
    const bool space = glfwGetKey(window, GLFW_KEY_SPACE) == GLFW_PRESS;
    if (space && !input.space_down) state.playing = !state.playing;
    input.space_down = space;
    const bool h = glfwGetKey(window, GLFW_KEY_H) == GLFW_PRESS;
    if (h && !input.h_down) state.panel = !state.panel;
    input.h_down = h;
    const bool r = glfwGetKey(window, GLFW_KEY_R) == GLFW_PRESS;
    if (r && !input.r_down)
        state.mode = state.mode == ViewMode::Rsl ? ViewMode::Rays : state.mode == ViewMode::Rays ? ViewMode::Split : ViewMode::Rsl;
    input.r_down = r;
    if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(window, GLFW_TRUE);
    state.environment_degrees = std::remainder(state.environment_degrees, 360.0f);
}

// Exposure (stops) that maps the 90th percentile of the vertex luminances to
// 0.7: the sun-lit scenes would otherwise clip.
float automatic_exposure(const VertexColors& colors) {
    std::vector<float> values;
    for (const auto& part : colors.parts)
        for (const Color& c : part)
            if (luminance(c) > 0.0f) values.push_back(luminance(c));
    if (values.empty()) return 0.0f;
    const size_t k = values.size() * 9 / 10;
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return std::log2(0.7f / values[k]);
}

void write_screenshot(const std::filesystem::path& path, int width, int height) {
    std::vector<unsigned char> pixels(size_t(width) * height * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
    std::vector<unsigned char> flipped(pixels.size());
    const size_t row = size_t(width) * 3;
    for (int y = 0; y < height; ++y)
        std::copy_n(pixels.data() + size_t(height - 1 - y) * row, row, flipped.data() + size_t(y) * row);
    write_file_atomically(path, encode_png(flipped.data(), width, height, 3));
}

// Set-up phase: the scene, with quick fields if asked for and a light to move
// around if it has none.
std::shared_ptr<Scene> load_viewer_scene(const ViewerOptions& options) {
    auto scene = std::make_shared<Scene>(load_scene(options.scene));
    if (options.quick_fields) use_quick_fields(scene->precompute);
    if (scene->lights.empty()) {  // a light to move around
        LocalLight light;
        light.radius = 0.05f;
        light.power = Color(4.0f);
        const BoundingSphere bounds = scene->parts.front().mesh.bounding_sphere();
        light.position = scene->camera.target + Vec3(0.5f, 1.0f, 0.5f) * std::max(0.5f, 0.3f * bounds.radius);
        scene->lights.push_back(light);
    }
    return scene;
}

// Set-up phase: the skybox of the environment (and its second map), or none without one.
std::unique_ptr<Skybox> make_skybox(const RenderSetup& setup) {
    std::unique_ptr<Skybox> skybox;
    if (setup.environment.resolution() > 0)
        skybox = std::make_unique<Skybox>(setup.environment, setup.second_environment.resolution() > 0
                                                                  ? &setup.second_environment
                                                                  : nullptr);
    return skybox;
}

// Set-up phase: the viewer's state from the options, the setup and the scene's camera.
void init_state(ViewerState& state, const ViewerOptions& options, Scene& scene, RenderSetup& setup,
                GlRenderer& renderer) {
    state.scene = &scene;
    state.environment = &setup.environment;
    if (setup.second_environment.resolution() > 0) state.second_environment = &setup.second_environment;
    state.renderer = &renderer;
    state.toggles = options.render;
    state.rsl_count = int(setup.environment_lights.first.lights.size());
    state.time = options.start_time;
    state.exposure = options.exposure;
    state.panel = options.panel;
    state.mode = options.view;
    state.reference_rays = options.reference_rays;
    state.camera.target = scene.camera.target;
    const Vec3 offset = scene.camera.position - scene.camera.target;
    state.camera.distance = glm::length(offset);
    state.camera.yaw = std::atan2(offset.x, offset.z);
    state.camera.pitch = std::asin(std::clamp(offset.y / std::max(state.camera.distance, 1e-6f), -1.0f, 1.0f));
    state.camera.fov_y_degrees = scene.camera.fov_y_degrees;
}

// Frame phase: the animation's step dt and the smoothed frame time; `last` becomes now.
float advance_frame_clock(const ViewerOptions& options, const Scene& scene, ViewerState& state,
                          std::chrono::steady_clock::time_point& last) {
    const auto now = std::chrono::steady_clock::now();
    // Screenshot mode plays at the scene's frame rate, whatever the speed.
    const float dt = options.frames > 0 ? 1.0f / std::max(scene.animation.fps, 1.0f)
                                        : std::chrono::duration<float>(now - last).count();
    const double ms = std::chrono::duration<double, std::milli>(now - last).count();
    state.frame_ms = 0.9 * state.frame_ms + 0.1 * ms;
    state.fps = state.frame_ms > 0 ? 1e3 / state.frame_ms : 0;
    last = now;
    return dt;
}

// Frame phase: ImGui's new frame, the user's input and panel, then the animation's time.
void update_from_user(GLFWwindow* window, Input& input, ViewerState& state, const Scene& scene, float dt,
                      float duration, int frame) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_input(window, input, state, dt);
    viewer_panel(state);
    apply_pending(state);
    if (state.playing && frame > 0)
        state.time = scene.animation.start + std::fmod(state.time - scene.animation.start + dt, duration);
}

// Where the frame is seen from: the environment's turn by the user and the camera's eye.
struct ViewPose {
    Mat3 turn;
    Vec3 eye;
};

// Frame phase: the pose of this frame's view, from the user's state.
ViewPose view_pose(const ViewerState& state) {
    const Mat3 turn = Mat3(glm::rotate(Mat4(1.0f), glm::radians(state.environment_degrees), Vec3(0, 1, 0)));
    const Vec3 eye = state.camera.eye();
    return {turn, eye};
}

// Frame phase: the ray-traced reference, made at its first use, given the
// renderer's materials, lights and toggles (rays for visibility instead of
// the fields).
GlRenderer& synced_reference(ViewerState& state) {
    RenderOptions options = state.toggles;
    options.shadow_maps.enabled = false;
    options.gpu_rays.enabled = true;
    options.gpu_rays.samples_per_side = state.reference_rays;
    if (!state.reference)
        state.reference = std::make_unique<GlRenderer>(*state.scene, state.renderer->environment_lights(), PartFields{},
                                                       options);
    state.reference->materials() = state.renderer->materials();  // tables are shared; only changed ones upload
    state.reference->set_toggles(options);
    return *state.reference;
}

// Frame phase: the renderers the mode shows shade the vertices at the pose;
// the first frame sets the automatic exposure from the first one's colours.
void shade_view(GlRenderer& renderer, const ViewPose& pose, const ViewerOptions& options, int frame,
                ViewerState& state) {
    std::vector<GlRenderer*> shown;
    if (state.mode != ViewMode::Rays) shown.push_back(&renderer);
    if (state.mode != ViewMode::Rsl) shown.push_back(&synced_reference(state));
    for (GlRenderer* r : shown) {
        r->set_view(state.time, pose.eye, pose.turn);
        r->shade_on_device();
    }
    if (frame == 0 && options.auto_exposure) {
        VertexColors colors = shown.front()->make_output();
        shown.front()->read_colors(colors);
        state.exposure = automatic_exposure(colors);
    }
}

// Frame phase: the skybox, the shaded scene and the panel into the window's framebuffer.
void draw_frame(GlRenderer& renderer, Skybox* skybox, const Scene& scene, const ViewerState& state,
                const ViewPose& pose, int width, int height) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glClearColor(0.05f, 0.05f, 0.06f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const float aspect = float(width) / float(std::max(height, 1));
    const Mat4 projection = glm::perspective(glm::radians(state.camera.fov_y_degrees), aspect,
                                             0.01f * state.camera.distance, 100.0f * state.camera.distance);
    const Mat4 view = glm::lookAt(pose.eye, state.camera.target, Vec3(0, 1, 0));
    if (skybox) {
        // The environment as the renderer turns its lights (FrameSetup):
        // the viewer's turn after the scene's rotation at t.
        const EnvironmentDesc& environment = scene.environment;
        const float weight = environment.second_file.empty() ? 0.0f : environment.blend_weight_at(state.time);
        skybox->draw(projection * view, pose.eye, pose.turn * environment.rotation_at(state.time), weight,
                     std::exp2(state.exposure));
    }
    const float exposure = std::exp2(state.exposure);
    if (state.mode == ViewMode::Split) {  // RSL on the left half, the reference on the right
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, width / 2, height);
        renderer.draw(projection * view, exposure);
        glScissor(width / 2, 0, width - width / 2, height);
        state.reference->draw(projection * view, exposure);
        glScissor(width / 2 - 1, 0, 2, height);  // the seam, a thin line
        glClearColor(0.9f, 0.9f, 0.9f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
    } else {
        (state.mode == ViewMode::Rays ? *state.reference : renderer).draw(projection * view, exposure);
    }
    glDisable(GL_DEPTH_TEST);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

// Set-up phase: the options the viewer runs with. In screenshot mode on a
// software renderer with the fallback asked for, the window shrinks to
// kSoftwareWidth pixels wide (the same aspect), the panel is hidden and the
// per-pixel passes are off: llvmpipe takes seconds a frame for them (docs/GPU.md).
ViewerOptions with_software_fallback(const ViewerOptions& options, GLFWwindow* window) {
    ViewerOptions view = options;
    if (options.frames < 1 || !options.software_fallback || !is_software_renderer()) return view;
    view.render.pixel_shadows = PixelShadows::Off;
    view.render.pixel_highlights = false;
    view.panel = false;
    if (options.width > ViewerOptions::kSoftwareWidth) {
        view.width = ViewerOptions::kSoftwareWidth;
        view.height = std::max(1, int(std::lround(double(options.height) * view.width / options.width)));
        glfwSetWindowSize(window, view.width, view.height);
    }
    if (options.software_fallback_applied) options.software_fallback_applied(view.width, view.height);
    return view;
}

}  // namespace

ViewMode parse_view_mode(const std::string& name) {
    if (name == "rsl") return ViewMode::Rsl;
    if (name == "rays") return ViewMode::Rays;
    if (name == "split") return ViewMode::Split;
    throw_error("view mode '{}': expected rsl, rays or split", name);
}

void run_viewer(const ViewerOptions& options) {
    const std::shared_ptr<Scene> scene = load_viewer_scene(options);
    SetupOptions how;
    how.progress = options.progress;
    RenderSetup setup = prepare_render(scene, options.render, how);

    Window window(options.width, options.height, "rsl view: " + scene->name);
    ImGuiSession imgui(window.window);
    if (options.notice) options.notice(context_description());
    const ViewerOptions view = with_software_fallback(options, window.window);
    GlRenderer renderer(*scene, setup.environment_lights, setup.fields, view.render);
    const std::unique_ptr<Skybox> skybox = make_skybox(setup);

    ViewerState state;
    init_state(state, view, *scene, setup, renderer);

    Input input;
    glfwGetCursorPos(window.window, &input.last_x, &input.last_y);
    const float duration = std::max(scene->animation.end - scene->animation.start, 1e-3f);
    auto last = std::chrono::steady_clock::now();
    for (int frame = 0; !glfwWindowShouldClose(window.window); ++frame) {
        const auto frame_start = std::chrono::steady_clock::now();
        const auto report_frame = [&] {
            if (options.frames > 0 && options.frame_done)
                options.frame_done(frame + 1, options.frames,
                                   std::chrono::duration<double>(std::chrono::steady_clock::now() - frame_start).count());
        };
        glfwPollEvents();
        const float dt = advance_frame_clock(options, *scene, state, last);
        update_from_user(window.window, input, state, *scene, dt, duration, frame);

        int width, height;
        glfwGetFramebufferSize(window.window, &width, &height);
        const ViewPose pose = view_pose(state);
        shade_view(renderer, pose, options, frame, state);
        draw_frame(renderer, skybox.get(), *scene, state, pose, width, height);

        if (options.frames > 0 && frame + 1 >= options.frames) {
            if (!options.screenshot.empty()) write_screenshot(options.screenshot, width, height);
            report_frame();
            break;
        }
        glfwSwapBuffers(window.window);
        report_frame();
    }
    if (state.refit.valid()) state.refit.wait();
    state.reference.reset();  // while the window's context is current
}

}  // namespace rsl::gl
