#include "tools/rsl/render_args.h"

#include "src/core/error.h"

namespace rsl::cli {

std::map<std::string, std::string> parse_material_overrides(const std::vector<std::string>& entries) {
    std::map<std::string, std::string> overrides;
    for (const std::string& entry : entries) {
        const size_t eq = entry.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
            throw_error("--material '{}': expected PART=MATERIAL", entry);
        overrides[entry.substr(0, eq)] = entry.substr(eq + 1);
    }
    return overrides;
}

}  // namespace rsl::cli
