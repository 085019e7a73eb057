// The scene file's part animation (docs/SCENE_FORMAT.md, "Animating parts").
#include "src/formats/part_animation.h"

#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "src/core/error.h"

namespace rsl {
namespace {

using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& key, const std::string& message) {
    throw_error("{}: {}", key, message);
}

float number(const Json& j, const std::string& key) {
    if (!j.is_number()) fail(key, fmt::format("expected a number, got {}", j.type_name()));
    const float v = j.get<float>();
    if (!std::isfinite(v)) fail(key, fmt::format("{} is not a finite number", j.dump()));
    return v;
}

std::vector<float> numbers(const Json& j, const std::string& key, size_t count) {
    if (!j.is_array() || j.size() != count)
        fail(key, fmt::format("expected an array of {} numbers, got {}", count, j.dump().substr(0, 80)));
    std::vector<float> out;
    for (size_t i = 0; i < count; ++i) out.push_back(number(j[i], fmt::format("{}[{}]", key, i)));
    return out;
}

// Keys of one channel: {"times": [...], "values": [...], "interpolation"}.
struct ChannelKeys {
    std::vector<float> times;
    const Json* values = nullptr;
    Interpolation interpolation = Interpolation::Linear;
};

ChannelKeys read_channel(const Json& j, const std::string& where) {
    if (!j.is_object()) fail(where, fmt::format("expected an object {{\"times\", \"values\"}}, got {}", j.type_name()));
    for (const auto& item : j.items())
        if (item.key() != "times" && item.key() != "values" && item.key() != "interpolation")
            fail(where + "." + item.key(), "unknown key (expected one of: times, values, interpolation)");
    if (!j.contains("times")) fail(where, "`times` is required");
    if (!j.contains("values")) fail(where, "`values` is required");
    ChannelKeys keys;
    const Json& times = j["times"];
    if (!times.is_array() || times.empty()) fail(where + ".times", "expected a non-empty array of times (seconds)");
    for (size_t k = 0; k < times.size(); ++k) {
        keys.times.push_back(number(times[k], fmt::format("{}.times[{}]", where, k)));
        if (k > 0 && !(keys.times[k] > keys.times[k - 1]))
            fail(fmt::format("{}.times[{}]", where, k),
                 fmt::format("times must increase: {:g} follows {:g} (times[{}])", keys.times[k], keys.times[k - 1], k - 1));
    }
    keys.values = &j["values"];
    if (!keys.values->is_array() || keys.values->size() != times.size())
        fail(where + ".values", fmt::format("expected an array of {} keys (one per time), got {}", times.size(),
                                            keys.values->is_array() ? fmt::format("{} keys", keys.values->size())
                                                                    : std::string(keys.values->type_name())));
    if (j.contains("interpolation")) {
        const Json& mode = j["interpolation"];
        if (mode == "linear") keys.interpolation = Interpolation::Linear;
        else if (mode == "step") keys.interpolation = Interpolation::Step;
        else fail(where + ".interpolation", fmt::format("expected \"linear\" or \"step\", got {}", mode.dump()));
    }
    return keys;
}

Vec3Track read_translation(const Json& j, const std::string& where) {
    const ChannelKeys keys = read_channel(j, where);
    Vec3Track track{keys.interpolation, keys.times, {}};
    for (size_t k = 0; k < keys.times.size(); ++k) {
        const std::vector<float> v = numbers((*keys.values)[k], fmt::format("{}.values[{}]", where, k), 3);
        track.values.emplace_back(v[0], v[1], v[2]);
    }
    return track;
}

// A key is a number (uniform) or [sx, sy, sz]; every factor positive.
Vec3Track read_scale(const Json& j, const std::string& where) {
    const ChannelKeys keys = read_channel(j, where);
    Vec3Track track{keys.interpolation, keys.times, {}};
    for (size_t k = 0; k < keys.times.size(); ++k) {
        const std::string key = fmt::format("{}.values[{}]", where, k);
        const Json& value = (*keys.values)[k];
        Vec3 s;
        if (value.is_number()) {
            s = Vec3(number(value, key));
        } else {
            const std::vector<float> v = numbers(value, key, 3);
            s = Vec3(v[0], v[1], v[2]);
        }
        if (!(s.x > 0 && s.y > 0 && s.z > 0))
            fail(key, fmt::format("scale must be positive, got {}", value.dump()));
        track.values.push_back(s);
    }
    return track;
}

// Keys are [ax, ay, az, degrees]: the part's orientation at that time (not an
// increment). Between keys the rotation slerps along the shorter arc, so a
// turn of 180° or more between two keys is ambiguous and refused.
QuatTrack read_rotation(const Json& j, const std::string& where) {
    const ChannelKeys keys = read_channel(j, where);
    QuatTrack track{keys.interpolation, keys.times, {}};
    std::vector<std::vector<float>> raw;
    for (size_t k = 0; k < keys.times.size(); ++k) {
        const std::string key = fmt::format("{}.values[{}]", where, k);
        const std::vector<float> v = numbers((*keys.values)[k], key + " ([axis x, y, z, degrees])", 4);
        const Vec3 axis(v[0], v[1], v[2]);
        if (glm::length(axis) == 0) {
            if (v[3] != 0) fail(key, "the axis is zero");
            track.values.emplace_back(1, 0, 0, 0);
        } else {
            track.values.push_back(glm::angleAxis(glm::radians(v[3]), glm::normalize(axis)));
        }
        raw.push_back(v);
    }
    // The turn between neighbours: from the quaternions, or as written when
    // both keys share an axis (0° to 270° about y is a turn of 270°, not 90°).
    for (size_t k = 1; k < raw.size() && keys.interpolation == Interpolation::Linear; ++k) {
        const float cosine = std::min(std::abs(glm::dot(track.values[k - 1], track.values[k])), 1.0f);
        float turn = glm::degrees(2.0f * std::acos(cosine));
        const Vec3 a0(raw[k - 1][0], raw[k - 1][1], raw[k - 1][2]), a1(raw[k][0], raw[k][1], raw[k][2]);
        const float lengths = glm::length(a0) * glm::length(a1);
        if (lengths > 0 && glm::length(glm::cross(a0, a1)) <= 1e-6f * lengths)
            turn = std::abs(raw[k][3] - (glm::dot(a0, a1) < 0 ? -raw[k - 1][3] : raw[k - 1][3]));
        if (turn >= 179.9f)
            fail(fmt::format("{}.values[{}]", where, k),
                 fmt::format("turns {:g}° from values[{}]; rotation keys slerp along the shorter arc, so neighbouring "
                             "keys must be less than 180° apart: add keys between them", turn, k - 1));
    }
    return track;
}

}  // namespace

void read_part_animation(const Json& animation, const std::string& where, SceneNode& node) {
    if (!animation.is_object())
        fail(where, fmt::format("expected an object with translation, rotation and/or scale, got {}", animation.type_name()));
    if (animation.empty()) fail(where, "give at least one of translation, rotation, scale");
    for (const auto& item : animation.items())
        if (item.key() != "translation" && item.key() != "rotation" && item.key() != "scale")
            fail(where + "." + item.key(), "unknown key (expected one of: translation, rotation, scale)");
    if (animation.contains("translation")) node.translation = read_translation(animation["translation"], where + ".translation");
    if (animation.contains("rotation")) node.rotation = read_rotation(animation["rotation"], where + ".rotation");
    if (animation.contains("scale")) node.scale = read_scale(animation["scale"], where + ".scale");
}

}  // namespace rsl
