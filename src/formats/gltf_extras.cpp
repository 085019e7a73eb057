// What a glTF file adds to its meshes: KHR_lights_punctual lights, cameras,
// and the extensions it uses (docs/SCENE_FORMAT.md, "glTF files").
#include <algorithm>
#include <cmath>
#include <numbers>

#include "src/core/error.h"
#include "src/formats/gltf_file.h"
#include "src/formats/gltf_model.h"

namespace rsl {

namespace {

struct ExtensionSupport {
    const char* name;
    bool honoured;
    const char* what;
};

// Extensions exporters write that rsl knows. Any other is "not supported".
constexpr ExtensionSupport kExtensions[] = {
    {"KHR_lights_punctual", true, "point and spot lights become sphere lights; directional lights become suns in the environment map"},
    {"KHR_mesh_quantization", true, "integer and normalized vertex attributes are read"},
    {"KHR_materials_emissive_strength", true, "emissiveStrength scales the material's emission"},
    {"KHR_texture_transform", false, "textures are not read"},
    {"KHR_texture_basisu", false, "textures are not read"},
    {"EXT_texture_webp", false, "textures are not read"},
    {"KHR_draco_mesh_compression", false, "compressed meshes cannot be read"},
    {"EXT_meshopt_compression", false, "compressed buffers cannot be read"},
    {"EXT_mesh_gpu_instancing", false, "a node renders once, without its instances"},
    {"KHR_materials_variants", false, "materials come from the scene file"},
    {"KHR_animation_pointer", false, "only node translation, rotation and scale are animated"},
};

const ExtensionSupport* find_extension(const std::string& name) {
    for (const ExtensionSupport& e : kExtensions)
        if (name == e.name) return &e;
    return nullptr;
}

std::string node_name(const tinygltf::Model& model, int n) {
    return model.nodes[n].name.empty() ? fmt::format("node{}", n) : model.nodes[n].name;
}

// The light index a node's KHR_lights_punctual entry names, or -1.
int node_light(const tinygltf::Model& model, const std::filesystem::path& path, int n) {
    const auto it = model.nodes[n].extensions.find("KHR_lights_punctual");
    if (it == model.nodes[n].extensions.end()) return -1;
    const tinygltf::Value& entry = it->second;
    if (!entry.IsObject() || !entry.Has("light") || !entry.Get("light").IsNumber())
        throw_file_error(path, "node '{}': KHR_lights_punctual has no light index", node_name(model, n));
    const double index = entry.Get("light").GetNumberAsDouble();
    if (!(index >= 0 && index < double(model.lights.size())) || index != std::floor(index))
        throw_file_error(path, "node '{}': light index {} is out of range ({} lights)", node_name(model, n), index,
                         model.lights.size());
    return int(index);
}

Color light_color(const tinygltf::Light& light, const std::filesystem::path& path, const std::string& where) {
    if (light.color.empty()) return Color(1);
    if (light.color.size() != 3) throw_file_error(path, "{}: color has {} values, expected 3", where, light.color.size());
    Color c;
    for (int i = 0; i < 3; ++i) {
        if (!(light.color[i] >= 0 && std::isfinite(light.color[i])))
            throw_file_error(path, "{}: color {} is not a finite non-negative number", where, light.color[i]);
        c[i] = float(light.color[i]);
    }
    return c;
}

}  // namespace

std::string gltf_extension_support(const std::string& name) {
    const ExtensionSupport* e = find_extension(name);
    if (e) return fmt::format("{}: {}", e->honoured ? "honoured" : "not supported", e->what);
    if (name.rfind("KHR_materials_", 0) == 0) return "not supported: materials come from the scene file";
    return "not supported: unknown to rsl";
}

bool gltf_extension_honoured(const std::string& name) {
    const ExtensionSupport* e = find_extension(name);
    return e && e->honoured;
}

namespace gltf {

void check_required_extensions(const tinygltf::Model& model, const std::filesystem::path& path) {
    for (const std::string& name : model.extensionsRequired)
        if (!gltf_extension_honoured(name))
            throw_file_error(path, "requires the glTF extension {}, which rsl does not support ({})", name,
                             gltf_extension_support(name));
}

// glTF gives a punctual light's intensity I in candela (lm/sr); rsl reads it
// as radiant intensity in the environment map's units per steradian (no
// 683 lm/W factor). The sphere light that has I on its axis has radiance
// L = I / (π a²) and power Φ = L·π·4πa² = 4π·I, times the light's colour.
// A directional light's intensity (lux) is read as irradiance the same way,
// and it becomes a sun (SunLight, scene_environment.h).
void import_lights(const tinygltf::Model& model, const std::filesystem::path& path, const SceneNodes& nodes,
                   Scene& scene) {
    std::vector<std::string> dropped, ranged;
    for (int n : nodes.order) {
        const int l = node_light(model, path, n);
        if (l < 0) continue;
        const tinygltf::Light& source = model.lights[l];
        const std::string name = node_name(model, n);
        const std::string where = fmt::format("light {} ('{}') on node '{}'", l, source.name, name);
        if (source.type != "point" && source.type != "spot" && source.type != "directional") {
            dropped.push_back(fmt::format("'{}' ({})", name, source.type));
            continue;
        }
        if (!(source.intensity >= 0 && std::isfinite(source.intensity)))
            throw_file_error(path, "{}: intensity {} is not a finite non-negative number", where, source.intensity);
        if (source.type == "directional") {  // lux, read as irradiance (as candela above): a sun
            scene.environment.suns.push_back(
                SunLight{name, nodes.scene_node[n], float(source.intensity) * light_color(source, path, where)});
            continue;
        }
        if (source.range > 0) ranged.push_back(fmt::format("'{}'", name));
        LocalLight light;
        light.name = name;
        light.radius = kGltfLightRadius;
        light.power = float(4.0 * std::numbers::pi * source.intensity) * light_color(source, path, where);
        light.node = nodes.scene_node[n];
        if (source.type == "spot") {
            const double inner = source.spot.innerConeAngle, outer = source.spot.outerConeAngle;
            if (!(inner >= 0 && inner < outer && outer <= 0.5 * std::numbers::pi + 1e-6))
                throw_file_error(path, "{}: cone angles {} .. {} (expected 0 ≤ innerConeAngle < outerConeAngle ≤ π/2)",
                                 where, inner, outer);
            light.spot = true;
            light.inner_cone_radians = float(inner);
            light.outer_cone_radians = float(std::min(outer, 0.5 * std::numbers::pi));
        }
        scene.lights.push_back(std::move(light));
    }
    if (!dropped.empty())
        warn_file(path, "light{} {} dropped: not a KHR_lights_punctual type (point, spot, directional)",
                  dropped.size() == 1 ? "" : "s", fmt::join(dropped, ", "));
    if (!ranged.empty())
        warn_file(path, "the range of light{} {} is ignored: rsl's lights fall off with the inverse square, without a cutoff",
                  ranged.size() == 1 ? "" : "s", fmt::join(ranged, ", "));
}

void import_camera(const tinygltf::Model& model, const std::filesystem::path& path, const SceneNodes& nodes,
                   Scene& scene) {
    std::vector<std::string> orthographic;
    std::optional<GltfCamera> found;
    for (int n : nodes.order) {
        const int c = model.nodes[n].camera;
        if (c < 0) continue;
        if (size_t(c) >= model.cameras.size())
            throw_file_error(path, "node '{}': camera index {} is out of range ({} cameras)", node_name(model, n), c,
                             model.cameras.size());
        const tinygltf::Camera& camera = model.cameras[c];
        if (camera.type != "perspective") {
            orthographic.push_back(fmt::format("'{}' ({})", node_name(model, n), camera.type));
            continue;
        }
        if (found) continue;
        const double yfov = camera.perspective.yfov;
        if (!(yfov > 0 && yfov < std::numbers::pi))
            throw_file_error(path, "camera {} on node '{}': yfov {} is not in (0, π)", c, node_name(model, n), yfov);
        found = GltfCamera{node_name(model, n), nodes.scene_node[n], float(yfov * 180.0 / std::numbers::pi)};
    }
    if (!orthographic.empty())
        warn_file(path, "camera node{} {} not used: rsl renders perspective cameras only",
                  orthographic.size() == 1 ? "" : "s", fmt::join(orthographic, ", "));
    if (found && !scene.gltf_camera) scene.gltf_camera = found;
}

}  // namespace gltf

}  // namespace rsl
