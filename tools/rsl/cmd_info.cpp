// `rsl info FILE...`: what an environment map, mesh or scene file holds.
// Other file kinds add themselves through RegisterInfoHandler (info.h).
#include <algorithm>
#include <cstdio>

#include <fmt/core.h>

#include "src/brdf/brdf.h"
#include "src/brdf/pbr_basis.h"
#include "tools/rsl/command.h"
#include "tools/rsl/info.h"
#include "tools/rsl/unique_meshes.h"
#include "src/core/emission.h"
#include "src/core/envmap.h"
#include "src/core/error.h"
#include "src/formats/environment_file.h"
#include "src/formats/gltf_file.h"
#include "src/formats/image_file.h"
#include "src/core/memory_limit.h"
#include "src/core/scene.h"
#include "src/formats/scene_environment.h"
#include "src/formats/scene_file.h"
#include "src/render/memory_estimate.h"

namespace rsl::cli {

std::vector<InfoHandler>& info_handler_registry() {
    static std::vector<InfoHandler> registry;
    return registry;
}

std::string lowercase_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

namespace {

std::string vec3_text(const Vec3& v) { return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x, v.y, v.z); }
std::string dvec3_text(const DVec3& v) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x, v.y, v.z); }

// ---- environment maps -----------------------------------------------------

void print_environment(const std::filesystem::path& path) {
    const Image image = read_hdr_image(path);
    const char* layout = image.width == 2 * image.height ? "latitude-longitude"
                         : image.height == 6 * image.width ? "cube (vertical strip)"
                                                            : "unrecognized";
    const bool declared = lowercase_extension(path) == ".exr" && read_exr_envmap_kind(path) != EnvmapKind::None;
    if (layout == std::string_view("unrecognized") && !declared) {
        // An image rsl rendered (or any HDR picture): no environment to describe.
        float peak = 0;
        double sum = 0;
        for (float v : image.pixels) peak = std::max(peak, v), sum += v;
        fmt::print("{}: HDR image (not an environment map layout)\n", path.string());
        fmt::print("  image:             {} x {}, {} channels\n", image.width, image.height, image.channels);
        fmt::print("  values:            mean {:.4g}, max {:.4g}\n", sum / double(std::max<size_t>(1, image.pixels.size())),
                   peak);
        return;
    }
    fmt::print("{}: environment map\n", path.string());
    fmt::print("  image:             {} x {}, {} channels, {} layout\n", image.width, image.height, image.channels, layout);
    constexpr int kResolution = 32;
    const CubeMap cube = load_environment(path, kResolution);
    fmt::print("  cube map:          6 x {} x {} texels\n", kResolution, kResolution);
    const DVec3 energy = cube.energy();
    fmt::print("  energy (∫L dω):    RGB {}\n", dvec3_text(energy));
    if (image.width == 2 * image.height) fmt::print("  source energy:     RGB {}\n", dvec3_text(latlong_energy(image)));

    int brightest = 0;
    for (int k = 1; k < cube.texel_count(); ++k)
        if (luminance(cube.radiance(k)) > luminance(cube.radiance(brightest))) brightest = k;
    const Vec3 dir = cube.texel_direction(brightest);
    const Color peak = cube.radiance(brightest);
    fmt::print("  brightest texel:   direction {}, radiance {}\n", vec3_text(dir), vec3_text(peak));
    const double total = luminance(Color(energy));
    if (total > 0)
        fmt::print("  its energy share:  {:.3g}% of the luminance in {:.3g}% of the sphere\n",
                   100.0 * luminance(peak) * cube.solid_angle(brightest) / total,
                   100.0 * cube.solid_angle(brightest) / (4 * kPi));
}

// ---- meshes and scenes ----------------------------------------------------

void print_mesh_bounds(const TriangleMesh& mesh, const char* indent) {
    const Bounds b = mesh.bounds();
    const BoundingSphere sphere = mesh.bounding_sphere();
    fmt::print("{}bounds {} .. {}, bounding sphere center {} radius {:.4g}\n", indent, vec3_text(b.lo), vec3_text(b.hi),
               vec3_text(sphere.center), sphere.radius);
}

bool is_animated(const Scene& scene, int node) {
    for (int n = node; n >= 0; n = scene.nodes[n].parent)
        if (scene.nodes[n].translation || scene.nodes[n].rotation || scene.nodes[n].scale) return true;
    return false;
}

void print_camera(const Scene& scene) {
    const Camera& c = scene.camera;
    const bool from_gltf = scene.gltf_camera && scene.gltf_camera->used;
    fmt::print("  camera:            {} → {}, fov {:.4g}°, {} x {}{}{}\n", vec3_text(c.position), vec3_text(c.target),
               c.fov_y_degrees, c.width, c.height, c.position_path || c.target_path ? ", keyed path" : "",
               from_gltf ? fmt::format(", glTF camera node '{}'", scene.gltf_camera->name)
               : scene.gltf_camera ? fmt::format(" (the scene file's; glTF camera node '{}' unused)", scene.gltf_camera->name)
                                   : "");
}

void print_parts(const Scene& scene) {
    size_t triangles = 0, dropped = 0, loaded = 0;
    for (const Part& p : scene.parts) {
        triangles += p.mesh.triangle_count();
        dropped += p.mesh.degenerate_dropped;
        loaded += p.loaded_vertices;
    }
    fmt::print("  parts:             {} ({} vertices, {} triangles, {} degenerate triangles dropped)\n",
               scene.parts.size(), scene.vertex_count(), triangles, dropped);
    const SubdivisionSettings& sub = scene.subdivision;
    fmt::print("  subdivision:       {}: {} vertices loaded, {} after\n",
               !sub.enabled          ? "off"
               : sub.absolute_edge > 0 ? fmt::format("edges up to {}", sub.absolute_edge)
                                       : fmt::format("edges up to {} x each part's bounding radius", sub.relative_edge),
               loaded, scene.vertex_count());
    const MemoryEstimate memory = estimate_render_memory(scene, true, true);
    fmt::print("  memory:            about {} to render (limit {})\n", memory_size_text(memory.bytes),
               memory_limit() ? memory_size_text(memory_limit()) : "none");
    for (size_t i = 0; i < scene.parts.size(); ++i) {
        const Part& part = scene.parts[i];
        const MaterialDesc& m = scene.materials.at(part.material);
        const Vec3 origin(scene.part_transform_at(int(i), scene.animation.start)[3]);
        const std::string dropped = part.mesh.degenerate_dropped
                                        ? fmt::format(" ({} degenerate dropped)", part.mesh.degenerate_dropped)
                                        : "";
        const std::string loaded_text =
            part.loaded_vertices != part.mesh.vertex_count() ? fmt::format(" ({} loaded)", part.loaded_vertices) : "";
        fmt::print("    {:<16} {:>7} vertices{} {:>7} triangles{}  material {} ({}){}  origin at {}\n", part.name,
                   part.mesh.vertex_count(), loaded_text, part.mesh.triangle_count(), dropped, m.name, m.model,
                   is_animated(scene, part.node) ? "  animated" : "", vec3_text(origin));
        if (part.skin) {
            const Skin& skin = scene.skins.at(size_t(part.skin->skin));
            size_t blended = 0;
            for (const JointWeights& w : part.skin->weights) blended += w[0] < 1.0f;
            fmt::print("      skin segment of mesh '{}' (skin '{}', joint '{}'): {} of its vertices blend several "
                       "joints (linear blend skinning)\n",
                       part.skin->mesh, skin.name, scene.nodes.at(size_t(part.node)).name, blended);
        }
        print_mesh_bounds(part.mesh, "      ");
    }
    if (!scene.skins.empty()) {
        size_t segments = 0;
        for (const Part& part : scene.parts) segments += part.skin != nullptr;
        fmt::print("  skins:             {} ({} segments, each a part moved by its joint; docs/design/SKINNING.md)\n",
                   scene.skins.size(), segments);
    }
    // Fields are per unique mesh: what `rsl bake` would bake, and what the
    // default cache (beside the file) already holds.
    const SceneFields plan = plan_fields(scene, default_field_options(scene));
    fmt::print("  unique meshes:     {} (fields are baked, stored and held once per unique mesh)\n",
               plan.unique.size());
    print_unique_meshes(stdout, scene, plan);
}

// Each glTF file's extensions (extensionsUsed), and what rsl does with each.
void print_gltf_extensions(const Scene& scene) {
    for (const GltfFileNotes& file : scene.gltf_files) {
        if (file.extensions_used.empty()) continue;
        fmt::print("  glTF extensions:   {}\n", file.file.filename().string());
        for (const std::string& name : file.extensions_used) {
            const bool required = std::find(file.extensions_required.begin(), file.extensions_required.end(), name) !=
                                  file.extensions_required.end();
            fmt::print("    {:<32} {}{}\n", name, gltf_extension_support(name), required ? " (required)" : "");
        }
    }
}

void print_lights(const Scene& scene) {
    fmt::print("  lights:            {}\n", scene.lights.size());
    for (const LocalLight& l : scene.lights) {
        std::string kind = l.name.empty() ? "" : fmt::format("glTF node '{}', ", l.name);
        if (l.spot)
            kind += fmt::format("spot {:.4g}°..{:.4g}° along {}, ", glm::degrees(l.inner_cone_radians),
                                glm::degrees(l.outer_cone_radians), vec3_text(l.axis));
        fmt::print("    {}radius {:.4g}, power {} W, position {}{}\n", kind, l.radius, vec3_text(l.power),
                   vec3_text(l.position),
                   l.path                           ? fmt::format(", path of {} keys", l.path->times.size())
                   : l.node >= 0 && is_animated(scene, l.node) ? ", animated"
                                                                : "");
    }
}

// What lights the scene from afar: its map, a uniform sky, glTF suns.
void print_environment_of(const Scene& scene) {
    const EnvironmentDesc& env = scene.environment;
    if (env.file.empty()) {
        fmt::print("  environment:       {}\n", describe_environment(env));
    } else {
        fmt::print("  environment:       {} (cube N = {}), rotation {}° + {}°/s about {}\n", env.file.string(),
                   env.resolution, env.rotation_degrees, env.rotation_degrees_per_second, vec3_text(env.rotation_axis));
        if (!env.second_file.empty())
            fmt::print("                     blends to {} over {} s\n", env.second_file.string(), env.blend_period_seconds);
        EnvironmentDesc added = env;  // what lights the scene besides the map
        added.file.clear();
        if (added.present()) fmt::print("                     with {}\n", describe_environment(added));
    }
    for (const SunLight& sun : env.suns)
        fmt::print("    sun {:<12} towards {}, irradiance {} (glTF directional light: a light of the sun's size)\n",
                   "'" + sun.name + "'", vec3_text(sun.direction_at(scene, scene.animation.start)),
                   vec3_text(sun.irradiance));
}

void print_materials(const Scene& scene) {
    fmt::print("  materials:         {}\n", scene.materials.size());
    for (const MaterialDesc& m : scene.materials) {
        std::string params;
        for (const auto& [key, values] : m.params) params += fmt::format(" {}={}", key, fmt::join(values, ","));
        // Emission: radiance the surface gives off itself (src/core/emission.h).
        if (emits(m))
            params += fmt::format(" emissive={},{},{}{}", m.emissive.r, m.emissive.g, m.emissive.b,
                                  m.emissive_texture ? fmt::format(" × texture '{}'", m.emissive_texture->name) : "");
        fmt::print("    {:<16} {}{}{}\n", m.name, m.model, params, m.file.empty() ? "" : " file " + m.file.string());
        if (const Texture* t = m.base_color_texture.get())
            fmt::print("    {:<16} base colour texture '{}' {}×{}\n", "", t->name, t->image.width, t->image.height);
        if (const Texture* t = m.metallic_roughness_texture.get()) {
            // What the renderers read per point (src/brdf/pbr_basis.h).
            const PbrLevelRange levels = pbr_level_range(m);
            fmt::print("    {:<16} metallic-roughness texture '{}' {}×{} ({}): roughness levels {:g} to {:g}{}\n", "",
                       t->name, t->image.width, t->image.height,
                       t->filter == TextureFilter::Nearest ? "nearest" : "bilinear",
                       shading::pbr_level_roughness(levels.first), shading::pbr_level_roughness(levels.last),
                       levels.metal ? ", metallic" : ", not metallic");
        }
    }
}

void print_scene_body(const Scene& scene) {
    print_parts(scene);
    print_materials(scene);
    print_environment_of(scene);
    print_lights(scene);
    print_camera(scene);
    print_gltf_extensions(scene);
    fmt::print("  animation:         {} .. {} s at {} fps\n", scene.animation.start, scene.animation.end,
               scene.animation.fps);
}

void print_mesh_file(const std::filesystem::path& path) {
    fmt::print("{}: mesh\n", path.string());
    const Scene scene = load_scene(path);  // .obj: one part; glTF: one part per mesh node
    fmt::print("  nodes:             {}{}\n", scene.nodes.size(), scene.gltf_files.empty() ? "" : " (the default scene's)");
    print_parts(scene);
    print_materials(scene);
    if (scene.animation.end > scene.animation.start)
        fmt::print("  animation:         {} .. {} s\n", scene.animation.start, scene.animation.end);
    print_environment_of(scene);  // the bare file's default sky, and its suns
    if (!scene.lights.empty()) print_lights(scene);
    if (scene.gltf_camera) print_camera(scene);
    print_gltf_extensions(scene);
}

void print_scene_file(const std::filesystem::path& path) {
    const Scene scene = load_scene(path);
    make_scene_brdfs(scene);  // checks every material's parameters (and reads measured BRDF files) up front
    fmt::print("{}: scene '{}'\n", path.string(), scene.name);
    print_scene_body(scene);
    const PrecomputeSettings& p = scene.precompute;
    fmt::print("  precompute:        SVDF {}² x{} rays, {} clusters, {} vectors; OVDF {} shells {}..{} r, cube {}, VDT {}, {} vectors\n",
               p.svdf_resolution, p.svdf_supersampling * p.svdf_supersampling, p.svdf_clusters, p.svdf_vectors,
               p.ovdf_shells, p.ovdf_inner_radius > 0 ? fmt::format("{}", p.ovdf_inner_radius) : "auto", p.ovdf_outer_radius, p.ovdf_cube_resolution, p.ovdf_vdt_resolution,
               p.ovdf_vectors);
}

bool has_extension(const std::filesystem::path& path, std::initializer_list<const char*> extensions) {
    const std::string ext = lowercase_extension(path);
    return std::any_of(extensions.begin(), extensions.end(), [&](const char* e) { return ext == e; });
}

RegisterInfoHandler environment_info({"environment", [](const auto& p) { return has_extension(p, {".exr", ".hdr"}); },
                                      print_environment});
RegisterInfoHandler mesh_info({"mesh", [](const auto& p) { return has_extension(p, {".obj", ".gltf", ".glb"}); },
                               print_mesh_file});
RegisterInfoHandler scene_info({"scene", [](const auto& p) { return has_extension(p, {".json"}) && !is_light_set_file(p); },
                                print_scene_file});

// ---- the command ----------------------------------------------------------

void run_info(const std::vector<std::filesystem::path>& files) {
    size_t failed = 0;
    for (const std::filesystem::path& file : files) {
        const auto& handlers = info_handler_registry();
        auto handler = std::find_if(handlers.begin(), handlers.end(), [&](const InfoHandler& h) { return h.accepts(file); });
        try {
            if (!std::filesystem::exists(file)) throw_file_error(file, "no such file");
            if (handler == handlers.end()) throw_file_error(file, "unknown file type '{}'", lowercase_extension(file));
            handler->print(file);
        } catch (const Error& e) {
            // Report every bad file, then fail once at the end.
            std::fflush(stdout);
            std::fprintf(stderr, "rsl: error: %s\n", e.what());
            ++failed;
        }
    }
    if (failed) throw_error("{} of {} files could not be read", failed, files.size());
}

RegisterCommand info_command(
    {"info", "Print what a file holds (environment map, mesh, scene, ...)", 10, [](CLI::App& app) {
         auto files = std::make_shared<std::vector<std::filesystem::path>>();
         app.add_option("files", *files,
                        "Files to describe: .exr/.hdr environment maps (size, layout, energy per channel, brightest "
                        "direction), .obj/.gltf/.glb meshes (counts, bounds, degenerate triangles), .json scenes "
                        "(parts, materials, environment, lights, camera, animation), and what rsl writes: .rslf fields, .rslv "
                        "per-vertex colours, .json light sets")
             ->required();
         app.callback([files] { run_info(*files); });
     }});

}  // namespace
}  // namespace rsl::cli
