#pragma once
// The renderer flags that `rsl render` and `rsl view` share.
#include <map>
#include <string>
#include <vector>

namespace rsl::cli {

// `--material PART=MATERIAL` entries → the overrides (RenderOptions::material_override);
// throws rsl::Error naming a malformed entry.
std::map<std::string, std::string> parse_material_overrides(const std::vector<std::string>& entries);

}  // namespace rsl::cli
