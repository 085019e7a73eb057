#include "src/render/culling.h"

namespace rsl {

namespace {

// How much occluder `o`'s field blends samples around the receiver sphere `r`:
// the receiver grown by it is what the culling tests see, so that culling
// never changes a lookup's result.
float footprint_growth(const BoundingSphere& r, const CullingPart& o, const BoundingSphere& reach) {
    const float scale = reach.radius / std::max(o.local_reach.radius, 1e-30f);
    const float distance = glm::length(r.center - reach.center) / scale;
    return scale * o.field->footprint(std::max(0.0f, distance - r.radius / scale),
                                      std::min(o.local_reach.radius, distance + r.radius / scale));
}

}  // namespace

void update_occluder_lists(std::span<const CullingPart> parts, const CullingLights& lights,
                           const RenderOptions& options, OccluderLists& out) {
    const size_t count = parts.size();
    const size_t environment = lights.environment.size();
    const size_t light_count = environment + lights.light_positions.size();
    out.occluders.clear();
    out.offsets.resize(count * light_count + 1);
    out.growth.assign(count * count, 0.0f);
    out.pairs = out.culled = 0;
    for (size_t receiver = 0; receiver < count; ++receiver)
        for (size_t o = 0; o < count; ++o)
            if (o != receiver && parts[o].field)
                out.growth[receiver * count + o] =
                    footprint_growth(parts[receiver].world_bounds, parts[o],
                                     transform_sphere(parts[o].transform, parts[o].local_reach));
    size_t slot = 0;
    for (size_t receiver = 0; receiver < count; ++receiver) {
        const BoundingSphere& r = parts[receiver].world_bounds;
        for (size_t l = 0; l < light_count; ++l) {
            out.offsets[slot++] = out.occluders.size();
            const bool lit = l < environment ? options.environment : options.local_lights;
            if (!options.occluders || !lit) continue;
            for (size_t o = 0; o < count; ++o) {
                if (o == receiver || !parts[o].field) continue;
                ++out.pairs;
                bool keep = true;
                if (options.occluder_culling) {
                    const BoundingSphere& occluder = parts[o].world_bounds;
                    const BoundingSphere reach = transform_sphere(parts[o].transform, parts[o].local_reach);
                    const BoundingSphere grown{r.center, r.radius + out.growth[receiver * count + o]};
                    if (beyond_reach(r, reach)) {
                        keep = false;
                    } else if (l < environment) {
                        const SquareLight& square = lights.environment[l];
                        keep = may_shadow_direction(grown, occluder, square.direction,
                                                    square_cone_half_angle(square.half_edge));
                    } else {
                        const size_t i = l - environment;
                        keep = may_shadow_sphere_light(grown, occluder, lights.light_positions[i],
                                                       lights.lights[i].radius);
                    }
                }
                if (keep)
                    out.occluders.push_back(int(o));
                else
                    ++out.culled;
            }
        }
    }
    out.offsets[slot] = out.occluders.size();
}

}  // namespace rsl
