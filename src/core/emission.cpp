#include "src/core/emission.h"

#include <cmath>

#include <fmt/format.h>

#include "src/core/error.h"
#include "src/core/scene_limits.h"

namespace rsl {

Color emission_at(const Color& emissive, const Texture* texture, const Vec2& uv) {
    return texture ? emissive * texture->lookup(uv) : emissive;  // the sampler's filter, as the GL passes
}

std::vector<Color> vertex_emission(const Color& emissive, const Texture* texture, const TriangleMesh& mesh) {
    std::vector<Color> emission(mesh.vertex_count(), emissive);
    if (texture) {
        RSL_CHECK_EQ(mesh.texcoords.size(), mesh.vertex_count());
        for (size_t v = 0; v < emission.size(); ++v) emission[v] = emission_at(emissive, texture, mesh.texcoords[v]);
    }
    return emission;
}

bool emission_fits(const MaterialDesc& m, const TriangleMesh& mesh) {
    return !emission_varies(m) || mesh.texcoords.size() == mesh.vertex_count();
}

std::string emission_problem(const Color& emissive) {
    for (int c = 0; c < 3; ++c)
        if (!(std::isfinite(emissive[c]) && emissive[c] >= 0.0f && emissive[c] <= kMaxEmission))
            return fmt::format("channel {} is {}: emission must be finite, at least 0 and at most {:g}", "RGB"[c],
                               emissive[c], kMaxEmission);
    return {};
}

Color checked_emission(const std::string& material, const std::vector<float>& value) {
    if (value.size() != 1 && value.size() != 3)
        throw_error("material '{}': parameter 'emissive' must be an RGB triple or one number, got {} values",
                    material, value.size());
    const Color emissive = value.size() == 1 ? Color(value[0]) : Color(value[0], value[1], value[2]);
    if (const std::string problem = emission_problem(emissive); !problem.empty())
        throw_error("material '{}': parameter 'emissive' {}", material, problem);
    return emissive;
}

}  // namespace rsl
