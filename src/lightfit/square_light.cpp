#include "src/lightfit/square_light.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/json_file.h"

namespace rsl {

namespace {
constexpr const char* kFormat = "rsl-lights";
constexpr int kVersion = 1;
// The fitting chart reaches the antipode at radius 2, so a square's
// half-diagonal can never exceed 2 (solid angle 8 sr).
constexpr float kMaxHalfDiagonal = 2.0f;

using nlohmann::json;

json vec_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

// Reads field `key` of object `j` with a readable error on absence or wrong type.
template <typename T>
T field(const std::filesystem::path& path, const json& j, const std::string& where, const char* key) {
    auto it = j.find(key);
    if (it == j.end()) throw_file_error(path, "{}: missing field '{}'", where, key);
    try {
        return it->get<T>();
    } catch (const json::exception&) {
        throw_file_error(path, "{}.{}: wrong type ({})", where, key, it->type_name());
    }
}

Vec3 vec_field(const std::filesystem::path& path, const json& j, const std::string& where, const char* key) {
    auto v = field<std::vector<double>>(path, j, where, key);
    if (v.size() != 3) throw_file_error(path, "{}.{}: expected 3 numbers, got {}", where, key, v.size());
    for (double x : v)
        if (!std::isfinite(x)) throw_file_error(path, "{}.{}: not finite", where, key);
    return Vec3(float(v[0]), float(v[1]), float(v[2]));
}

RotatableSquareLight parse_light(const std::filesystem::path& path, const json& j, const std::string& where) {
    if (!j.is_object()) throw_file_error(path, "{}: expected an object", where);
    RotatableSquareLight light;
    light.center = vec_field(path, j, where, "center");
    const float length = glm::length(light.center);
    if (std::abs(length - 1.0f) > 1e-3f)
        throw_file_error(path, "{}.center: not a unit vector (length {})", where, length);
    light.center /= length;
    light.half_diagonal = field<float>(path, j, where, "half_diagonal");
    if (!(light.half_diagonal > 0.0f && light.half_diagonal <= kMaxHalfDiagonal))
        throw_file_error(path, "{}.half_diagonal: must be in (0, {}], got {}", where, kMaxHalfDiagonal,
                         light.half_diagonal);
    light.radiance = vec_field(path, j, where, "radiance");
    if (light.radiance.r < 0 || light.radiance.g < 0 || light.radiance.b < 0)
        throw_file_error(path, "{}.radiance: negative component", where);
    light.texel_count = field<int>(path, j, where, "texel_count");
    if (light.texel_count < 0) throw_file_error(path, "{}.texel_count: negative", where);
    light.fit_error = field<float>(path, j, where, "fit_error");
    if (!(light.fit_error >= 0.0f) || !std::isfinite(light.fit_error))
        throw_file_error(path, "{}.fit_error: must be finite and non-negative", where);
    return light;
}
}  // namespace

DVec3 RslSet::total_energy() const {
    DVec3 sum(0.0);
    for (const auto& light : lights) sum += light.light_integral();
    return sum;
}

void RslSet::rotate(const Mat3& rotation) {
    for (auto& light : lights) light.center = glm::normalize(rotation * light.center);
    region_of_texel.clear();
    irradiance.reset();
}

void save_rsl_set(const std::filesystem::path& path, const RslSet& set) {
    json lights = json::array();
    for (const auto& light : set.lights)
        lights.push_back({{"center", vec_json(light.center)},
                          {"half_diagonal", light.half_diagonal},
                          {"solid_angle", light.solid_angle()},  // informative, not read back
                          {"radiance", vec_json(light.radiance)},
                          {"texel_count", light.texel_count},
                          {"fit_error", light.fit_error}});
    json root = {{"format", kFormat}, {"version", kVersion}, {"resolution", set.resolution}, {"lights", lights}};
    if (!set.region_of_texel.empty()) root["region_of_texel"] = set.region_of_texel;
    write_file_atomically(path, root.dump(1) + "\n");
}

RslSet load_rsl_set(const std::filesystem::path& path) {
    const json root = read_json_file(path);
    if (!root.is_object()) throw_file_error(path, "expected a JSON object at the top level");
    const auto format = field<std::string>(path, root, "file", "format");
    if (format != kFormat) throw_file_error(path, "format is '{}', expected '{}'", format, kFormat);
    const int version = field<int>(path, root, "file", "version");
    if (version != kVersion) throw_file_error(path, "unsupported version {} (this build reads {})", version, kVersion);

    RslSet set;
    set.resolution = field<int>(path, root, "file", "resolution");
    if (set.resolution <= 0 || set.resolution > 1 << 14)
        throw_file_error(path, "resolution {} out of range", set.resolution);
    const auto& lights = root.find("lights");
    if (lights == root.end() || !lights->is_array() || lights->empty())
        throw_file_error(path, "'lights' must be a non-empty array");
    for (size_t i = 0; i < lights->size(); ++i)
        set.lights.push_back(parse_light(path, (*lights)[i], fmt::format("lights[{}]", i)));

    if (root.contains("region_of_texel")) {
        set.region_of_texel = field<std::vector<int>>(path, root, "file", "region_of_texel");
        const size_t expected = size_t(6) * set.resolution * set.resolution;
        if (set.region_of_texel.size() != expected)
            throw_file_error(path, "region_of_texel has {} entries, expected 6×{}² = {}",
                             set.region_of_texel.size(), set.resolution, expected);
        const int count = int(set.lights.size());
        for (size_t t = 0; t < expected; ++t)
            if (set.region_of_texel[t] < 0 || set.region_of_texel[t] >= count)
                throw_file_error(path, "region_of_texel[{}] = {} is not a light index (0..{})", t,
                                 set.region_of_texel[t], count - 1);
    }
    return set;
}

}  // namespace rsl
