#include "src/render/vertex_renderer.h"

#include "src/core/emission.h"
#include "src/core/error.h"
#include "src/core/scene_limits.h"

namespace rsl {

namespace {

int find_part(const Scene& scene, const std::string& name) {
    for (size_t p = 0; p < scene.parts.size(); ++p)
        if (scene.parts[p].name == name) return int(p);
    return -1;
}

}  // namespace

void match_layers(const MaterialLibrary& library, const Scene& scene, VertexColors& out) {
    out.specular.resize(out.parts.size());
    out.textures.resize(out.parts.size());
    for (size_t p = 0; p < out.parts.size(); ++p) {
        const std::shared_ptr<const Texture>& texture = library.part_texture(int(p));
        if (texture && scene.parts[p].mesh.texcoords.size() != scene.parts[p].mesh.vertex_count())
            throw_file_error(scene.source, "part '{}': material '{}' has a base colour texture but the part has no "
                             "texture coordinates", scene.parts[p].name, library.desc(library.part_material(int(p))).name);
        if (bool(texture) != out.layered(p)) out.specular[p].assign(texture ? out.parts[p].size() : 0, Color(0));
        out.textures[p] = texture;
        const MaterialDesc& material = library.desc(library.part_material(int(p)));
        if (!emission_fits(material, scene.parts[p].mesh))
            throw_file_error(scene.source, "part '{}': material '{}' has an emissive texture but the part has no "
                             "texture coordinates", scene.parts[p].name, material.name);
    }
}

void add_emission(const MaterialLibrary& library, const Scene& scene, VertexColors& out) {
    RSL_CHECK_EQ(out.parts.size(), scene.parts.size());
    out.emission.assign(out.parts.size(), {});
    for (size_t p = 0; p < out.parts.size(); ++p) {
        const MaterialDesc& material = library.desc(library.part_material(int(p)));
        if (!emits(material)) continue;
        out.emission[p] = {material.emissive, material.emissive_texture};
        out.add_emission(p, vertex_emission(material, scene.parts[p].mesh));
    }
}

MaterialLibrary scene_material_library(const Scene& scene, const RenderOptions& options) {
    MaterialLibrary library = [&] {
        try {
            return MaterialLibrary::from_scene(scene, options.brdf_table);
        } catch (const Error& e) {
            if (scene.source.empty()) throw;
            throw_file_error(scene.source, "{}", e.what());
        }
    }();
    for (const auto& [part_name, material_name] : options.material_override) {
        const int part = find_part(scene, part_name);
        if (part < 0) throw_file_error(scene.source, "material override: no part named '{}'", part_name);
        const int material = library.find(material_name);
        if (material < 0)
            throw_file_error(scene.source, "material override for part '{}': no material named '{}'", part_name,
                             material_name);
        library.assign(part, material);
    }
    return library;
}

void VertexRenderer::set_part_material(const std::string& part, const std::string& material) {
    MaterialLibrary& library = materials();
    const int m = library.find(material);
    if (m < 0) throw_file_error(scene().source, "part '{}': no material named '{}'", part, material);
    const int p = find_part(scene(), part);
    if (p < 0) throw_file_error(scene().source, "no part named '{}' (to shade with material '{}')", part, material);
    library.assign(p, m);
}

void VertexRenderer::set_material_parameter(const std::string& material, const std::string& key,
                                            const std::vector<float>& value) {
    MaterialLibrary& library = materials();
    const int m = library.find(material);
    if (m < 0) throw_file_error(scene().source, "no material named '{}' (to set its parameter '{}')", material, key);
    library.set_parameter(m, key, value);
}

namespace {

void check_local_lights(const Scene& scene, const std::vector<LocalLight>& lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (const std::string problem = light_limit_problem(lights[i]); !problem.empty())
            throw_file_error(scene.source, "local light {}{}", i, problem);
}

// The fields checked against the scene's parts (an SVDF must have the
// mesh's vertex count), one entry per part (missing ones null).
PartFields checked_fields(const Scene& scene, PartFields fields) {
    const size_t parts = scene.parts.size();
    if (parts == 0) throw_file_error(scene.source, "scene '{}' has no parts", scene.name);
    fields.self.resize(parts);
    fields.occluder.resize(parts);
    for (size_t p = 0; p < parts; ++p)
        if (fields.self[p] && size_t(fields.self[p]->vertex_count()) != scene.parts[p].mesh.vertex_count())
            throw_file_error(scene.source, "part '{}': its SVDF has {} vertices, the mesh {}", scene.parts[p].name,
                             fields.self[p]->vertex_count(), scene.parts[p].mesh.vertex_count());
    return fields;
}

}  // namespace

VertexRenderer::VertexRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                               const RenderOptions& options)
    : scene_(scene),
      options_(options),
      environment_(std::move(environment_lights)),
      local_lights_(scene.lights),
      fields_(checked_fields(scene, std::move(fields))),
      library_(scene_material_library(scene, options)),
      frame_(scene, fields_) {}

void VertexRenderer::start() { set_local_lights(local_lights_); }

void VertexRenderer::set_local_lights(std::vector<LocalLight> lights) {
    check_local_lights(scene_, lights);
    local_lights_ = std::move(lights);
    frame_.reserve(environment_.light_count(), local_lights_.size());
    lights_changed();
    update_frame();
}

void VertexRenderer::set_environment_lights(EnvironmentLights lights) {
    environment_ = std::move(lights);
    frame_.reserve(environment_.light_count(), local_lights_.size());
    lights_changed();
    update_frame();
}

void VertexRenderer::set_time(float t) {
    time_ = t;
    view_rotation_ = Mat3(1.0f);
    view_camera_.reset();
    update_frame();
}

void VertexRenderer::set_view(float t, const Vec3& camera, const Mat3& environment_rotation) {
    time_ = t;
    view_rotation_ = environment_rotation;
    view_camera_ = camera;
    update_frame();
}

void VertexRenderer::update_frame() {
    frame_.update(scene_, environment_, local_lights_, options_, time_, view_rotation_, view_camera_);
    stats_.occluder_pairs = frame_.occluder_lists().pairs;
    stats_.occluder_pairs_culled = frame_.occluder_lists().culled;
    frame_changed();
}

VertexColors VertexRenderer::make_output() const {
    VertexColors colors;
    colors.scene_name = scene_.name;
    colors.producer = "rsl-" + backend();
    for (size_t p = 0; p < scene_.parts.size(); ++p)
        colors.add_part(scene_.parts[p].name, scene_.parts[p].mesh.vertex_count(), library_.part_texture(int(p)));
    return colors;
}

Image VertexRenderer::form_image(const VertexColors& colors, const PinholeCamera& camera,
                                 const ImageFormationOptions& options) {
    if (options.samples_per_side < 1) throw_error("image samples {}: expected at least 1", options.samples_per_side);
    if (camera.width < 1 || camera.height < 1)
        throw_error("image size {}×{}: expected at least one pixel", camera.width, camera.height);
    RSL_CHECK_EQ(colors.parts.size(), scene_.parts.size());
    return backend_image(colors, camera, options);
}

}  // namespace rsl
