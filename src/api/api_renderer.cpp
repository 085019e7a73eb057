// rsl::api::Renderer (include/rsl/rsl.h): what `rsl render` runs — a
// RenderSession: set-up, a backend's renderer, its image — and `rsl truth`'s
// ground truth, over one scene the setters edit.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "src/api/api_convert.h"
#include "src/api/renderer_state.h"
#include "src/core/scene_limits.h"
#include "src/image/image_formation.h"
#include "src/render/memory_estimate.h"
#include "src/trace/ground_truth.h"

namespace rsl::api {

int Renderer::State::part_index(const std::string& part) const {
    const auto& parts = scene().parts;
    for (size_t p = 0; p < parts.size(); ++p)
        if (parts[p].name == part) return int(p);
    std::vector<std::string> names;
    for (const Part& p : parts) names.push_back(p.name);
    throw_error("no part '{}' in scene '{}' (parts: {})", part, scene().name, fmt::join(names, ", "));
}

void Renderer::State::check_part(int part) const {
    if (part < 0 || part >= int(scene().parts.size()))
        throw_error("part {}: scene '{}' has {} parts", part, scene().name, scene().parts.size());
}

Renderer::Renderer(const Scene& scene, const RenderSettings& settings) : state_(std::make_unique<State>()) {
    State& s = *state_;
    if (settings.lights < 1) throw_error("lights {}: expected at least 1", settings.lights);
    const Backend backend = parse_backend(settings.backend);
    if (settings.ray_samples < 1 || settings.ray_samples > RenderOptions::kMaxRaySamples)
        throw_error("ray_samples {}: expected S of 1 to {} (S×S rays per vertex and light)", settings.ray_samples,
                    RenderOptions::kMaxRaySamples);
    if (settings.ray_samples != 1 && !backend_capabilities(backend).ray_samples)
        throw_error("ray_samples {}: the {} backend traces no rays (backends that do: {})", settings.ray_samples,
                    settings.backend, fmt::join(backends_with(&BackendCapabilities::ray_samples), ", "));
    s.options.ray_samples = settings.ray_samples;
    s.options.environment_light_count = settings.lights;
    s.options.cross_face_lights = settings.cross_face_lights;
    s.options.self_visibility = settings.self_visibility;
    s.options.occluders = settings.occluders;
    s.options.pixel_shadows = parse_pixel_shadows(settings.pixel_shadows);
    s.options.pixel_highlights = settings.pixel_highlights;
    s.options.exact_diffuse_light = settings.exact_diffuse_light;
    s.options.material_override = settings.part_materials;
    SetupOptions how;
    how.progress = throttled(settings.progress);
    how.field_cache = settings.field_cache;
    s.session = std::make_unique<RenderSession>(std::make_shared<rsl::Scene>(scene.internal()), s.options, backend, how);
    // The overrides hold from now on for the truth as well (the renderer has
    // checked them: scene_material_library).
    for (const auto& [part, material] : settings.part_materials) {
        auto& materials = s.scene().materials;
        for (size_t m = 0; m < materials.size(); ++m)
            if (materials[m].name == material) s.scene().parts[s.part_index(part)].material = int(m);
    }
    s.posed_node.assign(s.scene().parts.size(), -1);
}

Renderer::Renderer(Renderer&& other) noexcept = default;
Renderer& Renderer::operator=(Renderer&& other) noexcept = default;
Renderer::~Renderer() = default;

std::string Renderer::backend() const { return backend_name(state_->session->backend()); }
std::string Renderer::device() const { return state_->renderer().device(); }

SetupReport Renderer::setup() const {
    const RenderSetup& s = state_->session->setup();
    return {s.environment_lights.light_count(), s.fields_loaded, s.fields_baked, s.fit_seconds, s.bake_seconds};
}

std::vector<std::string> Renderer::part_names() const {
    std::vector<std::string> names;
    for (const Part& part : state_->scene().parts) names.push_back(part.name);
    return names;
}

std::vector<std::string> Renderer::input_files() const { return ::rsl::api::input_files(state_->scene()); }

std::array<float, 16> Renderer::part_transform(int part) const {
    state_->check_part(part);
    const Mat4 m = state_->scene().part_transform_at(part, state_->time);
    std::array<float, 16> out;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out[4 * c + r] = m[c][r];
    return out;
}

void Renderer::set_time(float t) {
    if (!std::isfinite(t)) throw_error("time {}: expected a finite number of seconds", t);
    state_->time = t;
    state_->frame_stale = true;
}

float Renderer::time() const { return state_->time; }

void Renderer::set_part_pose(int part, const Pose& pose) {
    State& s = *state_;
    s.check_part(part);
    rsl::Scene& scene = s.scene();
    const Transform transform = to_transform(pose, fmt::format("part '{}' pose", scene.parts[part].name));
    if (s.posed_node[part] < 0) {
        // A root node of its own: the part's old node may carry an animation
        // or other parts, and its parents their own motion.
        SceneNode node;
        node.name = scene.parts[part].name + " (posed)";
        scene.nodes.push_back(node);
        s.posed_node[part] = int(scene.nodes.size()) - 1;
        scene.parts[part].node = s.posed_node[part];
    }
    scene.nodes[s.posed_node[part]].rest = transform;
    s.frame_stale = true;
}

void Renderer::set_part_pose(const std::string& part, const Pose& pose) {
    set_part_pose(state_->part_index(part), pose);
}

void Renderer::set_environment_rotation(const Float3& axis, float degrees) {
    set_rotation(state_->scene().environment, axis, degrees, 0);
    state_->frame_stale = true;
}

void Renderer::set_camera(const Camera& camera) {
    if (camera.width < 1 || camera.height < 1 || camera.width > kMaxImageSide || camera.height > kMaxImageSide)
        throw_error("camera size {}×{}: expected 1 to {} pixels a side", camera.width, camera.height, kMaxImageSide);
    state_->scene().camera = to_camera(camera);
    state_->frame_stale = true;
}

void Renderer::set_sphere_lights(const std::vector<SphereLight>& lights) {
    std::vector<LocalLight> local;
    for (const SphereLight& light : lights) local.push_back(to_local_light(light));
    state_->renderer().set_local_lights(local);  // checks them
    state_->scene().lights = std::move(local);
    state_->frame_stale = true;
}

std::vector<SphereLight> Renderer::sphere_lights() const {
    std::vector<SphereLight> lights;
    for (const LocalLight& light : state_->renderer().local_lights()) lights.push_back(to_sphere_light(light));
    return lights;
}

void Renderer::set_environment_lights(const std::vector<SquareLight>& lights) {
    EnvironmentLights sets = state_->renderer().environment_lights();
    sets.first.lights.clear();
    sets.first.region_of_texel.clear();
    for (size_t i = 0; i < lights.size(); ++i) {
        const SquareLight& l = lights[i];
        const std::string what = fmt::format("environment light {}", i);
        RotatableSquareLight rsl;
        // Kept as given: the frame normalizes each center once it is rotated
        // (frame_setup.cpp), so a fitted set passed back shades bit for bit alike.
        rsl.center = finite_vec3(l.center, what + " center");
        if (glm::length(rsl.center) == 0) throw_error("{} center: (0, 0, 0) is no direction", what);
        if (!(l.half_diagonal > 0) || !std::isfinite(l.half_diagonal))
            throw_error("{}: half_diagonal {} must be positive", what, l.half_diagonal);
        rsl.half_diagonal = l.half_diagonal;
        rsl.radiance = finite_vec3(l.radiance, what + " radiance");
        if (rsl.radiance.r < 0 || rsl.radiance.g < 0 || rsl.radiance.b < 0)
            throw_error("{} radiance: negative", what);
        sets.first.lights.push_back(rsl);
    }
    state_->renderer().set_environment_lights(std::move(sets));
    state_->frame_stale = true;
}

std::vector<SquareLight> Renderer::environment_lights() const {
    std::vector<SquareLight> lights;
    for (const RotatableSquareLight& l : state_->renderer().environment_lights().first.lights)
        lights.push_back({to_float3(l.center), l.half_diagonal, to_float3(l.radiance)});
    return lights;
}

void Renderer::set_part_material(const std::string& part, const std::string& material) {
    State& s = *state_;
    s.renderer().set_part_material(part, material);  // checks both names
    const int index = s.renderer().materials().find(material);
    s.scene().parts[s.part_index(part)].material = index;
}

void Renderer::set_material_parameter(const std::string& material, const std::string& key,
                                      const std::vector<float>& value) {
    State& s = *state_;
    s.renderer().set_material_parameter(material, key, value);  // checks and rebuilds the table
    const int index = s.renderer().materials().find(material);
    // The library holds the scene's materials at the same indices (MaterialLibrary::from_scene).
    s.scene().materials.at(index) = s.renderer().materials().desc(index);
}

VertexColors Renderer::shade() {
    State& s = *state_;
    s.update_frame();
    // Colours alone: no image's terms to keep. A textured part's colour at
    // unit texture: its diffuse and specular layers summed (render_image
    // applies the texture per pixel).
    return to_api(s.session->shade(false).at_unit_texture());
}

std::pair<int, int> Renderer::State::image_size(const ImageSettings& settings) const {
    // The limits of `rsl render`: a 100000² image was a std::bad_alloc after minutes.
    if (settings.samples < 1 || settings.samples > kMaxPixelSamplesPerSide)
        throw_error("samples {}: expected 1 to {} (S×S primary rays per pixel)", settings.samples,
                    kMaxPixelSamplesPerSide);
    if (settings.width < 0 || settings.height < 0 || settings.width > kMaxImageSide || settings.height > kMaxImageSide)
        throw_error("image size {}×{}: expected 1 to {} pixels a side (or 0: the camera's)", settings.width,
                    settings.height, kMaxImageSide);
    const int width = settings.width > 0 ? settings.width : scene().camera.width;
    const int height = settings.height > 0 ? settings.height : scene().camera.height;
    if (std::pair(width, height) != memory_checked_size) {  // the estimate walks the scene: once per size
        check_render_memory(scene(), options.self_visibility, options.occluders, width, height);
        memory_checked_size = {width, height};
    }
    return {width, height};
}

// Any colours (the caller's, edited or blended): their image alone, with
// textures per pixel and no renderer's per-pixel terms.
Image Renderer::State::form_image(const ::rsl::VertexColors& colors, const ImageSettings& settings) const {
    const State& s = *this;
    const auto [width, height] = image_size(settings);
    // As `rsl render`: made posed at the first frame, then moved to each.
    if (!s.posed) s.posed = std::make_unique<PosedScene>(s.scene(), s.time);
    s.posed->set_time(s.time);
    ImageFormationOptions formation;
    formation.samples_per_side = settings.samples;
    return to_api(::rsl::form_image(*s.posed, PinholeCamera::at_time(s.scene().camera, s.time, width, height), colors,
                                    formation));
}

Image Renderer::form_image(const VertexColors& colors, const ImageSettings& settings) const {
    return state_->form_image(to_internal(colors, "form_image colours"), settings);
}

Image Renderer::render_image(const ImageSettings& settings) {
    State& s = *state_;
    s.update_frame();
    const auto [width, height] = s.image_size(settings);
    s.session->shade(true);
    // The renderer's own image of its colours (per-pixel shadows and
    // highlights, textures per pixel), as `rsl render`'s.
    ImageFormationOptions formation;
    formation.samples_per_side = settings.samples;
    return to_api(s.session->image(s.session->camera(width, height), formation));
}

VertexColors Renderer::truth(const TruthSettings& settings) const {
    const State& s = *state_;
    if (settings.subdivision < 1 || settings.subdivision > 16)
        throw_error("subdivision {}: expected 1 to 16", settings.subdivision);
    const rsl::Scene& scene = s.scene();
    // The environment `rsl truth` integrates: the scene's map (a blend's two)
    // at the scene's resolution, black without one.
    const CubeMap environment =
        s.session->setup().environment.resolution() > 0 ? s.session->setup().environment_at(s.time)
                                                        : CubeMap(scene.environment.resolution);
    GroundTruthOptions options;
    options.texel_subdivision = settings.subdivision;
    options.local_lights = settings.local_lights;
    const GroundTruth truth(scene, environment, s.time, options);
    const Progress progress = throttled(settings.progress);
    ProgressCallback callback;
    if (progress)
        callback = [&](size_t done, size_t total) { progress("truth", double(done) / double(std::max<size_t>(total, 1))); };
    VertexColors colors = to_api(truth.shade_vertices(callback));
    if (progress) progress("truth", 1.0);
    return colors;
}

}  // namespace rsl::api
