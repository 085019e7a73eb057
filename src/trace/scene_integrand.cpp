#include "src/trace/scene_integrand.h"

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/brdf/pbr_basis.h"
#include "src/core/emission.h"
#include "src/core/error.h"
#include "src/core/sphere_light.h"

namespace rsl {

SceneLobes::SceneLobes(const Scene& scene) {
    lobe = make_scene_brdfs(scene);
    whole = lobe;
    specular.assign(lobe.size(), nullptr);
    for (size_t m = 0; m < scene.materials.size(); ++m)
        if (scene.materials[m].base_color_texture) {
            BrdfLobes lobes = make_brdf_lobes(scene.materials[m]);
            lobe[m] = std::move(lobes.diffuse);
            specular[m] = std::move(lobes.specular);
        }
    varies.assign(lobe.size(), 0);
    for (size_t m = 0; m < scene.materials.size(); ++m) varies[m] = varies_per_point(scene.materials[m]) ? 1 : 0;
    for (const Part& part : scene.parts) {
        if (part.material >= 0 && part.material < int(lobe.size()) && varies[size_t(part.material)] &&
            part.mesh.texcoords.size() != part.mesh.positions.size())
            throw_file_error(scene.source, "part '{}': its material has a metallic-roughness texture, the part no "
                             "texture coordinates", part.name);
        if (part.material < 0 || part.material >= int(lobe.size()))
            throw_file_error(scene.source, "part '{}' has material index {} of {}", part.name, part.material,
                             lobe.size());
        if (specular[size_t(part.material)] && part.mesh.texcoords.size() != part.mesh.positions.size())
            throw_file_error(scene.source, "part '{}': its material has a base colour texture, the part no "
                             "texture coordinates", part.name);
        if (!emission_fits(scene.materials[size_t(part.material)], part.mesh))
            throw_file_error(scene.source, "part '{}': its material has an emissive texture, the part no texture "
                             "coordinates", part.name);
        if (part.mesh.normals.size() != part.mesh.positions.size())
            throw_file_error(scene.source, "part '{}' has {} normals for {} vertices", part.name,
                             part.mesh.normals.size(), part.mesh.positions.size());
    }
    for (const LocalLight& light : scene.lights)
        if (!(light.radius > 0.0f)) throw_file_error(scene.source, "local light with radius {}", light.radius);
}

std::shared_ptr<const Brdf> SceneLobes::at_point(const Scene& scene, int material, const Vec2& uv,
                                                 bool specular_lobe) const {
    const MaterialDesc& desc = scene.materials[size_t(material)];
    const MaterialDesc at = material_at_point(desc, pbr_point(desc, uv));
    if (!desc.base_color_texture) return make_brdf(at);
    BrdfLobes lobes = make_brdf_lobes(at);
    return specular_lobe ? lobes.specular : lobes.diffuse;
}

void PosedLights::set(const Scene& scene, float t) {
    positions.clear(), axes.clear(), cones.clear();
    for (const LocalLight& light : scene.lights) {
        positions.push_back(light.position_at(scene, t));
        axes.push_back(light.axis_at(scene, t));
        cones.push_back(spot_cone_scale_offset(light));
    }
}

VertexColors shade_every_vertex(const Scene& scene, const SceneLobes& lobes, const std::string& producer, float time,
                                size_t grain, const std::function<Color(int part, int vertex, bool specular)>& shade,
                                const ProgressCallback& progress) {
    VertexColors colors;
    colors.scene_name = scene.name;
    colors.producer = producer;
    colors.time = time;
    std::vector<size_t> first;  // flattened index of each part's first vertex
    size_t total = 0;
    for (const Part& part : scene.parts) {
        const bool layered = lobes.specular[size_t(part.material)] != nullptr;
        colors.add_part(part.name, part.mesh.vertex_count(),
                        layered ? scene.materials[size_t(part.material)].base_color_texture : nullptr);
        first.push_back(total);
        total += part.mesh.vertex_count();
    }
    std::atomic<size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, total, grain), [&](const tbb::blocked_range<size_t>& range) {
        int part = int(std::upper_bound(first.begin(), first.end(), range.begin()) - first.begin()) - 1;
        for (size_t index = range.begin(); index != range.end(); ++index) {
            while (part + 1 < int(first.size()) && index >= first[size_t(part + 1)]) ++part;
            const int vertex = int(index - first[size_t(part)]);
            colors.parts[size_t(part)][size_t(vertex)] = shade(part, vertex, false);
            if (colors.layered(size_t(part))) colors.specular[size_t(part)][size_t(vertex)] = shade(part, vertex, true);
        }
        const size_t now = done.fetch_add(range.size()) + range.size();
        if (progress) progress(now, total);
    });
    // What a surface gives off itself, as the renderers add it (add_emission, src/render/vertex_renderer.h).
    colors.emission.assign(scene.parts.size(), {});
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const MaterialDesc& material = scene.materials[size_t(scene.parts[p].material)];
        if (!emits(material)) continue;
        colors.emission[p] = {material.emissive, material.emissive_texture};
        colors.add_emission(p, vertex_emission(material, scene.parts[p].mesh));
    }
    return colors;
}

}  // namespace rsl
