#include "src/render/vertex_renderer.h"

#include "src/core/error.h"

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

void VertexRenderer::check_local_lights(const Scene& scene, const std::vector<LocalLight>& lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (!(lights[i].radius > 0.0f))
            throw_file_error(scene.source, "local light {} with radius {} (expected > 0)", i, lights[i].radius);
}

}  // namespace rsl
