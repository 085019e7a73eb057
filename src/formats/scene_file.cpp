// Scene loading: JSON scene files (docs/SCENE_FORMAT.md), or a single
// .gltf/.glb/.obj with defaults. Every error names the file and the key.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <type_traits>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "src/core/envmap.h"
#include "src/core/emission.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"
#include "src/formats/gltf_camera.h"
#include "src/formats/gltf_file.h"
#include "src/formats/json_file.h"
#include "src/formats/obj_loader.h"
#include "src/formats/part_animation.h"
#include "src/core/precompute_limits.h"
#include "src/core/scene.h"
#include "src/core/scene_limits.h"
#include "src/formats/scene_file.h"

namespace rsl {

namespace {

using Json = nlohmann::json;

std::string lowercase_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

MaterialDesc builtin_default_material() {
    MaterialDesc m;
    m.name = "default";
    m.model = "lambert";
    m.params["albedo"] = {0.7f, 0.7f, 0.7f};
    return m;
}

// Time range covered by every keyed track in the scene ([0, 0] when static).
std::pair<float, float> keyed_time_range(const Scene& scene) {
    float lo = 1e30f, hi = -1e30f;
    auto cover = [&](const std::vector<float>& times) {
        if (times.empty()) return;
        lo = std::min(lo, times.front());
        hi = std::max(hi, times.back());
    };
    for (const SceneNode& n : scene.nodes) {
        if (n.translation) cover(n.translation->times);
        if (n.rotation) cover(n.rotation->times);
        if (n.scale) cover(n.scale->times);
    }
    for (const LocalLight& l : scene.lights)
        if (l.path) cover(l.path->times);
    if (scene.camera.position_path) cover(scene.camera.position_path->times);
    if (scene.camera.target_path) cover(scene.camera.target_path->times);
    if (lo > hi) return {0.0f, 0.0f};
    return {lo, hi};
}

// World-space bounds of all parts at time t (transformed box corners).
Bounds world_bounds_at(const Scene& scene, float t) {
    Bounds world;
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const Bounds local = scene.parts[p].mesh.bounds();
        const Mat4 m = scene.part_transform_at(int(p), t);
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 c((corner & 1) ? local.hi.x : local.lo.x, (corner & 2) ? local.hi.y : local.lo.y,
                         (corner & 4) ? local.hi.z : local.lo.z);
            world.extend(Vec3(m * Vec4(c, 1.0f)));
        }
    }
    return world;
}

// A camera that sees the whole scene from the front (+Z), slightly above.
void frame_camera(Scene& scene) {
    const Bounds b = world_bounds_at(scene, scene.animation.start);
    if (b.empty()) return;
    const float radius = std::max(0.5f * glm::length(b.hi - b.lo), 1e-3f);
    const float half_fov = glm::radians(scene.camera.fov_y_degrees) * 0.5f;
    const float distance = 1.1f * radius / std::sin(half_fov);
    scene.camera.target = b.center();
    scene.camera.position = b.center() + distance * glm::normalize(Vec3(0, 0.35f, 1));
    scene.camera.up = Vec3(0, 1, 0);
}

// has_camera_pose: the scene file's camera gives a pose (a camera with only
// a size keeps the glTF camera's pose); has_camera: it has a camera at all.
void finish_scene(Scene& scene, bool has_camera, bool has_camera_pose, bool has_animation) {
    if (!has_animation) {
        const auto [start, end] = keyed_time_range(scene);
        scene.animation.start = start;
        scene.animation.end = end;
    }
    // A glTF light's pose at the start, for what shows or edits lights without the scene's nodes.
    for (LocalLight& light : scene.lights) {
        if (light.node < 0) continue;
        light.position = light.position_at(scene, scene.animation.start);
        light.axis = light.axis_at(scene, scene.animation.start);
    }
    if (has_camera_pose) return;
    if (scene.gltf_camera) use_gltf_camera(scene, world_bounds_at(scene, scene.animation.start));
    else if (!has_camera) frame_camera(scene);
}

// Reads one JSON scene file. Keys are checked against the schema as they are
// read, so a misspelt key is an error instead of a silently ignored setting.
class SceneFileReader {
public:
    explicit SceneFileReader(const std::filesystem::path& path) : path_(path), dir_(path.parent_path()) {}

    Scene read() {
        const Json root = parse_file();
        if (!root.is_object()) fail("", "the top level must be a JSON object");
        check_keys(root, "", {"name", "gltf", "gltf_animations", "parts", "materials", "part_materials", "environment",
                              "lights", "light_radii", "camera", "animation", "precompute", "subdivision"});
        scene_.source = path_;
        scene_.name = root.contains("name") ? string_at(root, "name", "name") : path_.stem().string();
        read_materials(root);
        const Json part_materials = root.value("part_materials", Json::object());
        if (!part_materials.is_object()) fail("part_materials", "expected an object (part name → material name)");
        default_material_ = choose_default_material(part_materials);
        // "*" overrides every part's material, a glTF's own included.
        if (part_materials.contains("*")) gltf_material_use_ = GltfMaterialUse::Override;

        if (root.contains("gltf")) {
            const size_t first = scene_.parts.size();
            const std::filesystem::path file = existing_file(root["gltf"], "gltf");
            const std::vector<std::string> clips = gltf_animations(root, "gltf_animations");
            nested([&] { load_gltf_into(file, scene_, default_material_, gltf_material_use_, clips); }, "gltf");
            assign_materials(first, part_materials);
        } else if (root.contains("gltf_animations")) {
            fail("gltf_animations", "names animations of the top-level `gltf`, and the scene has none");
        }
        if (root.contains("parts")) read_parts(root["parts"], part_materials);
        if (scene_.parts.empty()) fail("", "the scene has no parts (give `gltf` or `parts`)");
        check_part_material_names(part_materials);
        if (root.contains("light_radii")) read_light_radii(root["light_radii"]);

        if (root.contains("environment")) read_environment(root["environment"]);
        if (root.contains("lights")) read_lights(root["lights"]);
        if (root.contains("camera")) read_camera(root["camera"]);
        if (root.contains("animation")) read_animation(root["animation"]);
        if (root.contains("precompute")) read_precompute(root["precompute"]);
        if (root.contains("subdivision")) read_subdivision(root["subdivision"]);
        subdivide_scene_parts(scene_);
        const bool has_camera = root.contains("camera");
        const bool has_pose = has_camera && std::any_of(kCameraPoseKeys.begin(), kCameraPoseKeys.end(),
                                                        [&](const char* key) { return root["camera"].contains(key); });
        finish_scene(scene_, has_camera, has_pose, root.contains("animation"));
        return std::move(scene_);
    }

private:
    // A key holds the file's own names (materials, parts), so it is quoted as echo_value allows.
    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        if (key.empty()) throw_file_error(path_, "{}", message);
        throw_file_error(path_, "{}: {}", echo_value(key), message);
    }

    // Runs a loader of a file the scene names; its error (which names that
    // file) is prefixed with the scene file and the key.
    template <typename F>
    std::invoke_result_t<F> nested(F&& load, const std::string& key) const {
        try {
            return load();
        } catch (const Error& e) {
            fail(key, e.what());
        }
    }

    Json parse_file() const { return read_json_file(path_); }

    void check_keys(const Json& object, const std::string& where, std::initializer_list<const char*> allowed) const {
        for (const auto& item : object.items()) {
            const std::string& key = item.key();  // not a structured binding: clang 14 cannot capture one
            const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; });
            if (!known) {
                std::string list;
                for (const char* a : allowed) list += fmt::format("{}{}", list.empty() ? "" : ", ", a);
                fail(where.empty() ? key : where + "." + key, fmt::format("unknown key (expected one of: {})", list));
            }
        }
    }

    static std::string join(const std::string& where, const std::string& key) {
        return where.empty() ? key : where + "." + key;
    }

    const Json& expect_object(const Json& j, const std::string& key) const {
        if (!j.is_object()) fail(key, fmt::format("expected an object, got {}", j.type_name()));
        return j;
    }

    float number(const Json& j, const std::string& key) const {
        if (!j.is_number()) fail(key, fmt::format("expected a number, got {}", j.type_name()));
        const float v = j.get<float>();
        if (!std::isfinite(v)) fail(key, "value is not finite");
        return v;
    }
    float number_at(const Json& object, const char* name, const std::string& where) const {
        return number(object.at(name), join(where, name));
    }
    float positive_number_at(const Json& object, const char* name, const std::string& where) const {
        const float v = number_at(object, name, where);
        if (!(v > 0)) fail(join(where, name), fmt::format("must be positive, got {}", v));
        return v;
    }
    // least ≤ value ≤ most: the limits of docs/SCENE_FORMAT.md, beyond which
    // a value is a typo or a corrupt file and the buffers it sizes would not
    // fit (or, below, the fields' lookups would have no second tap).
    int int_at(const Json& object, const char* name, const std::string& where, int least, int most) const {
        const Json& j = object.at(name);
        if (!j.is_number_integer()) fail(join(where, name), fmt::format("expected an integer, got {}", j.dump()));
        const long long v = j.is_number_unsigned() && j.get<unsigned long long>() > (1ull << 62) ? -1 : j.get<long long>();
        if (v < least || v > most)
            fail(join(where, name), fmt::format("must be an integer from {} to {}, got {}", least, most, j.dump()));
        return int(v);
    }
    int int_at(const Json& object, const char* name, const std::string& where, const PrecomputeLimit& limit) const {
        return int_at(object, name, where, limit.least, limit.most);
    }
    std::string string_at(const Json& object, const char* name, const std::string& key) const {
        const Json& j = object.at(name);
        if (!j.is_string()) fail(key, fmt::format("expected a string, got {}", j.type_name()));
        return j.get<std::string>();
    }
    std::vector<float> numbers(const Json& j, const std::string& key, size_t expected_count = 0) const {
        std::vector<float> out;
        if (j.is_number()) {
            out.push_back(number(j, key));
        } else if (j.is_array()) {
            for (size_t i = 0; i < j.size(); ++i) out.push_back(number(j[i], fmt::format("{}[{}]", key, i)));
        } else {
            fail(key, fmt::format("expected a number or an array of numbers, got {}", j.type_name()));
        }
        if (expected_count && out.size() != expected_count)
            fail(key, fmt::format("expected {} numbers, got {}", expected_count, out.size()));
        return out;
    }
    Vec3 vec3(const Json& j, const std::string& key) const {
        if (!j.is_array()) fail(key, fmt::format("expected an array of 3 numbers, got {}", j.type_name()));
        const std::vector<float> v = numbers(j, key, 3);
        return Vec3(v[0], v[1], v[2]);
    }
    Vec3 vec3_at(const Json& object, const char* name, const std::string& where) const {
        return vec3(object.at(name), join(where, name));
    }

    // Every file a scene file names comes through here, and is recorded as an input.
    std::filesystem::path existing_file(const Json& j, const std::string& key) {
        if (!j.is_string()) fail(key, fmt::format("expected a file name, got {}", j.type_name()));
        const std::filesystem::path file = dir_ / j.get<std::string>();
        if (const std::string why = why_not_regular_file(file); !why.empty()) fail(key, fmt::format("file {} {}", echo_value(file.string()), why));
        scene_.input_files.push_back(file);
        return file;
    }

    void read_materials(const Json& root) {
        if (!root.contains("materials")) return;
        const Json& materials = expect_object(root["materials"], "materials");
        for (const auto& [name, entry] : materials.items()) {
            const std::string where = "materials." + name;
            expect_object(entry, where);
            MaterialDesc m;
            m.name = name;
            for (const auto& [key, value] : entry.items()) {
                if (key == "model") {
                    m.model = string_at(entry, "model", join(where, key));
                } else if (key == "file") {
                    m.file = existing_file(value, join(where, key));
                } else if (key == "emissive") {  // any model's; not a BRDF parameter (src/core/emission.h)
                    const std::vector<float> rgb = numbers(value, join(where, key));
                    if (rgb.size() != 1 && rgb.size() != 3)
                        fail(join(where, key), fmt::format("expected an RGB triple or one number, got {} values", rgb.size()));
                    m.emissive = rgb.size() == 1 ? Color(rgb[0]) : Color(rgb[0], rgb[1], rgb[2]);
                    if (const std::string problem = emission_problem(m.emissive); !problem.empty())
                        fail(join(where, key), problem);
                } else {
                    m.params[key] = numbers(value, join(where, key));
                }
            }
            material_index_[name] = int(scene_.materials.size());
            scene_.materials.push_back(std::move(m));
        }
    }

    int material_named(const std::string& name, const std::string& key) const {
        auto it = material_index_.find(name);
        if (it == material_index_.end()) fail(key, fmt::format("no material named '{}' in `materials`", echo_value(name)));
        return it->second;
    }

    // `part_materials["*"]`, else a material named "default", else a built-in Lambert.
    int choose_default_material(const Json& part_materials) {
        if (part_materials.contains("*")) return material_named(string_at(part_materials, "*", "part_materials.*"), "part_materials.*");
        if (auto it = material_index_.find("default"); it != material_index_.end()) return it->second;
        scene_.materials.push_back(builtin_default_material());
        return int(scene_.materials.size()) - 1;
    }

    // part_materials[part name] for the parts from first_part on (others keep the default).
    void assign_materials(size_t first_part, const Json& part_materials) {
        for (size_t p = first_part; p < scene_.parts.size(); ++p) {
            Part& part = scene_.parts[p];
            if (part_materials.contains(part.name)) {
                const std::string key = "part_materials." + part.name;
                part.material = material_named(string_at(part_materials, part.name.c_str(), key), key);
            }
        }
    }

    void check_part_material_names(const Json& part_materials) const {
        for (const auto& item : part_materials.items()) {
            const std::string& name = item.key();  // not a structured binding: clang 14 cannot capture one
            if (name == "*") continue;
            const bool found = std::any_of(scene_.parts.begin(), scene_.parts.end(),
                                           [&](const Part& p) { return p.name == name; });
            if (!found) fail("part_materials." + name, "no part has this name");
        }
    }

    Transform read_transform(const Json& j, const std::string& where) const {
        expect_object(j, where);
        check_keys(j, where, {"translation", "rotation_axis_angle", "scale"});
        Transform t;
        if (j.contains("translation")) t.translation = vec3_at(j, "translation", where);
        if (j.contains("rotation_axis_angle")) {
            const std::vector<float> v = numbers(j["rotation_axis_angle"], join(where, "rotation_axis_angle"), 4);
            const Vec3 axis(v[0], v[1], v[2]);
            if (glm::length(axis) == 0 && v[3] != 0) fail(join(where, "rotation_axis_angle"), "the axis is zero");
            if (v[3] != 0) t.rotation = glm::angleAxis(glm::radians(v[3]), glm::normalize(axis));
        }
        if (j.contains("scale")) {
            const std::vector<float> s = numbers(j["scale"], join(where, "scale"));
            if (s.size() == 1) t.scale = Vec3(s[0]);
            else if (s.size() == 3) t.scale = Vec3(s[0], s[1], s[2]);
            else fail(join(where, "scale"), "expected a number or 3 numbers");
            if (!(t.scale.x > 0 && t.scale.y > 0 && t.scale.z > 0)) fail(join(where, "scale"), "must be positive");
        }
        return t;
    }

    // `gltf_animations`: one animation name or a list of them (the glTF's
    // animations that play); absent: every animation.
    std::vector<std::string> gltf_animations(const Json& object, const std::string& where) {
        if (!object.contains("gltf_animations")) return {};
        const Json& value = object["gltf_animations"];
        if (value.is_string()) return {value.get<std::string>()};
        if (!value.is_array() || value.empty())
            fail(where, "expected an animation name or a non-empty list of them");
        std::vector<std::string> names;
        for (size_t i = 0; i < value.size(); ++i) {
            if (!value[i].is_string()) fail(fmt::format("{}[{}]", where, i), "expected an animation name (a string)");
            names.push_back(value[i].get<std::string>());
        }
        return names;
    }

    void read_parts(const Json& parts, const Json& part_materials) {
        if (!parts.is_array()) fail("parts", fmt::format("expected an array, got {}", parts.type_name()));
        for (size_t i = 0; i < parts.size(); ++i) {
            const std::string where = fmt::format("parts[{}]", i);
            const Json& entry = expect_object(parts[i], where);
            check_keys(entry, where, {"name", "obj", "gltf", "gltf_animations", "transform", "animation", "material"});
            if (entry.contains("obj") == entry.contains("gltf")) fail(where, "give exactly one of `obj` and `gltf`");
            if (entry.contains("gltf_animations") && !entry.contains("gltf"))
                fail(where + ".gltf_animations", "names animations of the entry's `gltf`, and it has none");
            // The entry's static transform is a node; the file's nodes hang below it.
            SceneNode holder;
            holder.rest = entry.contains("transform") ? read_transform(entry["transform"], where + ".transform") : Transform{};
            if (entry.contains("animation")) {
                try {
                    read_part_animation(entry["animation"], where + ".animation", holder);
                } catch (const Error& e) {
                    fail("", e.what());
                }
            }
            const std::string name = entry.contains("name") ? string_at(entry, "name", where + ".name") : "";
            const int holder_index = int(scene_.nodes.size());
            const size_t first_part = scene_.parts.size();
            if (entry.contains("obj")) {
                const std::filesystem::path file = existing_file(entry["obj"], where + ".obj");
                holder.name = name.empty() ? file.stem().string() : name;
                scene_.nodes.push_back(holder);
                Part part;
                part.mesh = nested([&] { return load_obj(file); }, where + ".obj");
                part.name = holder.name;
                part.node = holder_index;
                part.material = default_material_;
                scene_.parts.push_back(std::move(part));
            } else {
                const std::filesystem::path file = existing_file(entry["gltf"], where + ".gltf");
                holder.name = name.empty() ? file.stem().string() : name;
                scene_.nodes.push_back(holder);
                const size_t first_node = scene_.nodes.size();
                const std::vector<std::string> clips = gltf_animations(entry, where + ".gltf_animations");
                nested([&] { load_gltf_into(file, scene_, default_material_, gltf_material_use_, clips); },
                       where + ".gltf");
                for (size_t n = first_node; n < scene_.nodes.size(); ++n)
                    if (scene_.nodes[n].parent < 0) scene_.nodes[n].parent = holder_index;
                // A named entry names its part; several parts get "name/node".
                const size_t added = scene_.parts.size() - first_part;
                for (size_t p = first_part; p < scene_.parts.size() && !name.empty(); ++p)
                    scene_.parts[p].name = added == 1 ? name : name + "/" + scene_.parts[p].name;
            }
            assign_materials(first_part, part_materials);
            if (entry.contains("material")) {
                const int m = material_named(string_at(entry, "material", where + ".material"), where + ".material");
                for (size_t p = first_part; p < scene_.parts.size(); ++p) scene_.parts[p].material = m;
            }
        }
    }

    void read_environment(const Json& j) {
        const std::string where = "environment";
        expect_object(j, where);
        check_keys(j, where, {"file", "resolution", "rotation", "second_file", "blend_period_seconds"});
        EnvironmentDesc& env = scene_.environment;
        if (!j.contains("file")) fail(where, "`file` is required");
        env.file = existing_file(j["file"], "environment.file");
        if (j.contains("resolution")) env.resolution = int_at(j, "resolution", where, 1, kMaxCubeResolution);
        if (j.contains("rotation")) {
            const Json& r = expect_object(j["rotation"], "environment.rotation");
            check_keys(r, "environment.rotation", {"axis", "degrees", "degrees_per_second"});
            if (r.contains("axis")) {
                env.rotation_axis = vec3_at(r, "axis", "environment.rotation");
                if (glm::length(env.rotation_axis) == 0) fail("environment.rotation.axis", "the axis is zero");
                env.rotation_axis = glm::normalize(env.rotation_axis);
            }
            if (r.contains("degrees")) env.rotation_degrees = number_at(r, "degrees", "environment.rotation");
            if (r.contains("degrees_per_second"))
                env.rotation_degrees_per_second = number_at(r, "degrees_per_second", "environment.rotation");
        }
        if (j.contains("second_file")) env.second_file = existing_file(j["second_file"], "environment.second_file");
        if (j.contains("blend_period_seconds")) env.blend_period_seconds = positive_number_at(j, "blend_period_seconds", where);
        if (!env.second_file.empty() && env.blend_period_seconds == 0)
            fail("environment.blend_period_seconds", "required with `second_file`");
    }

    // {"times": [...], "<values_key>": [[x, y, z], ...]} → a linear track.
    Vec3Track read_path(const Json& path, const std::vector<float>& times, const char* values_key,
                        const std::string& where) const {
        Vec3Track track;
        track.times = times;
        const std::string key = join(where, values_key);
        if (!path.contains(values_key)) fail(key, "required with `times`");
        const Json& values = path[values_key];
        if (!values.is_array() || values.size() != times.size())
            fail(key, fmt::format("expected an array of {} points (one per time)", times.size()));
        for (size_t k = 0; k < values.size(); ++k) track.values.push_back(vec3(values[k], fmt::format("{}[{}]", key, k)));
        return track;
    }
    std::vector<float> read_times(const Json& path, const std::string& where) const {
        if (!path.contains("times")) fail(where, "`times` is required");
        const std::vector<float> times = numbers(path["times"], join(where, "times"));
        if (times.empty()) fail(join(where, "times"), "needs at least one time");
        for (size_t k = 1; k < times.size(); ++k)
            if (times[k] <= times[k - 1]) fail(join(where, "times"), "times must increase");
        return times;
    }

    // Radii of the glTF files' lights (named after their nodes); "*" for every one.
    void read_light_radii(const Json& j) {
        expect_object(j, "light_radii");
        for (const auto& item : j.items()) {
            const std::string& name = item.key();  // not a structured binding: clang 14 cannot capture one
            positive_number_at(j, name.c_str(), "light_radii");  // checked here, applied below
            const bool found = std::any_of(scene_.lights.begin(), scene_.lights.end(),
                                           [&](const LocalLight& l) { return !l.name.empty() && l.name == name; });
            if (name != "*" && !found) fail("light_radii." + name, "no glTF light is on a node of this name");
        }
        for (LocalLight& light : scene_.lights) {
            if (light.name.empty()) continue;  // a scene-file light gives its own radius
            if (j.contains(light.name)) light.radius = number(j[light.name], "light_radii." + light.name);
            else if (j.contains("*")) light.radius = number(j["*"], "light_radii.*");
        }
    }

    void read_lights(const Json& lights) {
        if (!lights.is_array()) fail("lights", fmt::format("expected an array, got {}", lights.type_name()));
        for (size_t i = 0; i < lights.size(); ++i) {
            const std::string where = fmt::format("lights[{}]", i);
            const Json& j = expect_object(lights[i], where);
            check_keys(j, where, {"radius", "power", "position", "path"});
            LocalLight light;
            if (j.contains("radius")) light.radius = positive_number_at(j, "radius", where);
            if (j.contains("power")) {
                light.power = vec3_at(j, "power", where);
                if (light.power.r < 0 || light.power.g < 0 || light.power.b < 0) fail(where + ".power", "must not be negative");
            }
            if (j.contains("position")) light.position = vec3_at(j, "position", where);
            if (j.contains("path")) {
                const Json& path = expect_object(j["path"], where + ".path");
                check_keys(path, where + ".path", {"times", "positions"});
                light.path = read_path(path, read_times(path, where + ".path"), "positions", where + ".path");
                if (!j.contains("position")) light.position = light.path->values.front();
            }
            scene_.lights.push_back(light);
        }
    }

    void read_camera(const Json& j) {
        const std::string where = "camera";
        expect_object(j, where);
        check_keys(j, where, {"position", "target", "up", "fov_degrees", "width", "height", "path"});
        Camera& c = scene_.camera;
        if (j.contains("position")) c.position = vec3_at(j, "position", where);
        if (j.contains("target")) c.target = vec3_at(j, "target", where);
        if (j.contains("up")) c.up = vec3_at(j, "up", where);
        if (j.contains("fov_degrees")) {
            c.fov_y_degrees = positive_number_at(j, "fov_degrees", where);
            if (c.fov_y_degrees >= 180) fail("camera.fov_degrees", "must be below 180");
        }
        if (j.contains("width")) c.width = int_at(j, "width", where, 1, kMaxImageSide);
        if (j.contains("height")) c.height = int_at(j, "height", where, 1, kMaxImageSide);
        if (j.contains("path")) {
            const Json& path = expect_object(j["path"], "camera.path");
            check_keys(path, "camera.path", {"times", "positions", "targets"});
            const std::vector<float> times = read_times(path, "camera.path");
            if (path.contains("positions")) c.position_path = read_path(path, times, "positions", "camera.path");
            if (path.contains("targets")) c.target_path = read_path(path, times, "targets", "camera.path");
        }
        if (glm::length(c.position - c.target) == 0) fail("camera", "position and target coincide");
    }

    void read_animation(const Json& j) {
        expect_object(j, "animation");
        check_keys(j, "animation", {"start", "end", "fps"});
        AnimationRange& a = scene_.animation;
        if (j.contains("start")) a.start = number_at(j, "start", "animation");
        if (j.contains("end")) a.end = number_at(j, "end", "animation");
        if (j.contains("fps")) a.fps = positive_number_at(j, "fps", "animation");
        if (a.end < a.start) fail("animation.end", fmt::format("{} is before start {}", a.end, a.start));
    }

    void read_precompute(const Json& j) {
        expect_object(j, "precompute");
        check_keys(j, "precompute", {"svdf", "ovdf"});
        PrecomputeSettings& p = scene_.precompute;
        if (j.contains("svdf")) {
            const Json& s = expect_object(j["svdf"], "precompute.svdf");
            const std::string w = "precompute.svdf";
            check_keys(s, w, {"resolution", "clusters", "vectors", "supersampling"});
            if (s.contains("resolution")) p.svdf_resolution = int_at(s, "resolution", w, kSvdfResolutionLimit);
            if (s.contains("clusters")) p.svdf_clusters = int_at(s, "clusters", w, kSvdfClustersLimit);
            if (s.contains("vectors")) p.svdf_vectors = int_at(s, "vectors", w, kSvdfVectorsLimit);
            if (s.contains("supersampling")) p.svdf_supersampling = int_at(s, "supersampling", w, kSvdfSupersamplingLimit);
        }
        if (j.contains("ovdf")) {
            const Json& o = expect_object(j["ovdf"], "precompute.ovdf");
            const std::string w = "precompute.ovdf";
            check_keys(o, w, {"shells", "inner_radius", "outer_radius", "cube_resolution", "vdt_resolution", "vectors"});
            if (o.contains("shells")) p.ovdf_shells = int_at(o, "shells", w, kOvdfShellsLimit);
            // "auto" (the default): chosen per mesh (src/fields/ovdf.h ovdf_params_for_mesh).
            if (o.contains("inner_radius")) {
                if (o["inner_radius"].is_string() && o["inner_radius"] != "auto")
                    fail("precompute.ovdf.inner_radius", "must be a positive number or \"auto\"");
                p.ovdf_inner_radius = o["inner_radius"] == "auto" ? 0.0f : positive_number_at(o, "inner_radius", w);
            }
            if (o.contains("outer_radius")) p.ovdf_outer_radius = positive_number_at(o, "outer_radius", w);
            if (o.contains("cube_resolution")) p.ovdf_cube_resolution = int_at(o, "cube_resolution", w, kOvdfCubeResolutionLimit);
            if (o.contains("vdt_resolution")) p.ovdf_vdt_resolution = int_at(o, "vdt_resolution", w, kOvdfVdtResolutionLimit);
            if (o.contains("vectors")) p.ovdf_vectors = int_at(o, "vectors", w, kOvdfVectorsLimit);
        }
        // The rules between settings, as `rsl bake` checks its flags.
        if (const auto problem = precompute_problem(p)) fail("precompute." + problem->key, problem->message);
    }

    // `false` (off), `true` (the default edge) or {enabled, relative_edge,
    // edge}: an object turns it on unless its `enabled` is false.
    void read_subdivision(const Json& j) {
        SubdivisionSettings& s = scene_.subdivision;
        if (j.is_boolean()) {
            s.enabled = j.get<bool>();
            return;
        }
        expect_object(j, "subdivision");
        check_keys(j, "subdivision", {"enabled", "relative_edge", "edge"});
        s.enabled = true;
        if (j.contains("enabled")) {
            if (!j["enabled"].is_boolean()) fail("subdivision.enabled", "expected true or false");
            s.enabled = j["enabled"].get<bool>();
        }
        if (j.contains("relative_edge")) s.relative_edge = positive_number_at(j, "relative_edge", "subdivision");
        if (j.contains("edge")) s.absolute_edge = positive_number_at(j, "edge", "subdivision");
    }

    static constexpr std::array<const char*, 5> kCameraPoseKeys{"position", "target", "up", "fov_degrees", "path"};

    std::filesystem::path path_, dir_;
    Scene scene_;
    std::map<std::string, int> material_index_;
    int default_material_ = 0;
    GltfMaterialUse gltf_material_use_ = GltfMaterialUse::Convert;
};

// A bare mesh file: one part per mesh (node), a Lambert material, a framing
// camera, and a uniform white sky (radiance 1) with the file's suns, so that
// a mesh or an exporter's glTF, which carries no environment, renders lit.
Scene scene_from_mesh_file(const std::filesystem::path& path, bool gltf) {
    Scene scene;
    scene.source = path;
    scene.name = path.stem().string();
    scene.materials.push_back(builtin_default_material());
    if (gltf) {
        load_gltf_into(path, scene, 0);
        if (scene.parts.empty()) throw_file_error(path, "no mesh node with triangles");
    } else {
        SceneNode node;
        node.name = scene.name;
        scene.nodes.push_back(node);
        Part part;
        part.mesh = load_obj(path);
        part.name = scene.name;
        part.node = 0;
        scene.parts.push_back(std::move(part));
    }
    scene.environment.uniform = Color(1.0f);
    scene.subdivision.enabled = false;  // no scene file, so no way to switch it off: as loaded
    subdivide_scene_parts(scene);
    finish_scene(scene, false, false, false);
    return scene;
}

}  // namespace

Scene load_scene(const std::filesystem::path& path) {
    check_regular_file(path);
    const std::string ext = lowercase_extension(path);
    Scene scene;
    if (ext == ".json") scene = SceneFileReader(path).read();
    else if (ext == ".gltf" || ext == ".glb") scene = scene_from_mesh_file(path, true);
    else if (ext == ".obj") scene = scene_from_mesh_file(path, false);
    else throw_file_error(path, "unknown scene type '{}' (expected .json, .gltf, .glb or .obj)", ext);
    scene.input_files.insert(scene.input_files.begin(), path);
    check_light_limits(scene, path);
    check_part_transforms(scene, path);
    return scene;
}

}  // namespace rsl
