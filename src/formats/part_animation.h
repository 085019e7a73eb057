#pragma once
// Keyframed animation of a scene file's `parts[i]` entry (docs/SCENE_FORMAT.md,
// "Animating parts"): translation, rotation (axis-angle keys, slerped) and
// scale tracks on the entry's node, for OBJ and glTF entries alike.
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "src/core/scene.h"

namespace rsl {

// Reads `animation` (the JSON object at key `where`, e.g. "parts[1].animation")
// into node's tracks; a channel it does not give keeps node.rest. Throws
// rsl::Error "<where>.<key>: <what is wrong>" naming the key and the key
// frame (the caller prefixes the scene file).
void read_part_animation(const nlohmann::json& animation, const std::string& where, SceneNode& node);

}  // namespace rsl
