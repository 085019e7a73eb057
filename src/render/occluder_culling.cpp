#include "src/render/occluder_culling.h"

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
    out.growth.clear();
    out.offsets.resize(count * light_count + 1);
    out.pairs = out.culled = out.candidates = 0;
    out.light_words = (light_count + 31) / 32;
    out.candidate_offsets.resize(count + 1);
    out.candidate_occluders.clear();
    out.candidate_growths.clear();
    out.candidate_lights.clear();
    out.reaches.clear();
    out.field_parts.clear();
    for (size_t o = 0; o < count; ++o) {
        if (!parts[o].field) continue;
        out.field_parts.push_back(int(o));
        out.reaches.push_back(transform_sphere(parts[o].transform, parts[o].local_reach));
    }
    const bool culling = options.occluder_culling;
    if (culling) out.reach_tree.build(out.reaches);
    size_t lit = 0;
    for (size_t l = 0; l < light_count; ++l) lit += (l < environment ? options.environment : options.local_lights) ? 1 : 0;
    if (!options.occluders) lit = 0;

    size_t slot = 0;
    for (size_t receiver = 0; receiver < count; ++receiver) {
        const BoundingSphere& r = parts[receiver].world_bounds;
        // The candidates: every other part with a field, or with culling those
        // whose reach the receiver lies in (the tree's superset, then the exact test).
        out.candidate_parts.clear();
        out.candidate_growth.clear();
        const size_t others = out.field_parts.size() - (parts[receiver].field ? 1 : 0);
        out.pairs += others * lit;
        if (lit > 0 && culling) {
            out.reach_tree.overlapping(r, out.candidate_parts);
            size_t kept = 0;
            for (const int index : out.candidate_parts) {
                const int o = out.field_parts[size_t(index)];
                if (size_t(o) == receiver || beyond_reach(r, out.reaches[size_t(index)])) continue;
                out.candidate_parts[kept++] = o;
                out.candidate_growth.push_back(footprint_growth(r, parts[size_t(o)], out.reaches[size_t(index)]));
            }
            out.candidate_parts.resize(kept);
        } else if (lit > 0) {
            for (const int o : out.field_parts)
                if (size_t(o) != receiver) out.candidate_parts.push_back(o);
            out.candidate_growth.assign(out.candidate_parts.size(), 0.0f);
        }
        out.candidates += out.candidate_parts.size();
        const size_t first_candidate = out.candidate_occluders.size();
        out.candidate_offsets[receiver] = first_candidate;
        out.candidate_occluders.insert(out.candidate_occluders.end(), out.candidate_parts.begin(),
                                       out.candidate_parts.end());
        out.candidate_growths.insert(out.candidate_growths.end(), out.candidate_growth.begin(),
                                     out.candidate_growth.end());
        out.candidate_lights.resize(out.candidate_occluders.size() * out.light_words, 0u);
        for (size_t l = 0; l < light_count; ++l) {
            out.offsets[slot++] = out.occluders.size();
            const bool light_on = l < environment ? options.environment : options.local_lights;
            if (!options.occluders || !light_on) continue;
            for (size_t c = 0; c < out.candidate_parts.size(); ++c) {
                const int o = out.candidate_parts[c];
                const float growth = out.candidate_growth[c];
                bool keep = true;
                if (culling) {
                    const BoundingSphere& occluder = parts[size_t(o)].world_bounds;
                    const BoundingSphere grown{r.center, r.radius + growth};
                    if (l < environment) {
                        const SquareLight& square = lights.environment[l];
                        keep = may_shadow_direction(grown, occluder, square.direction,
                                                    square_cone_half_angle(square.half_edge));
                    } else {
                        const size_t i = l - environment;
                        keep = may_shadow_sphere_light(grown, occluder, lights.light_positions[i],
                                                       lights.lights[i].radius);
                    }
                }
                if (keep) {
                    out.occluders.push_back(o);
                    out.growth.push_back(growth);
                    out.candidate_lights[(first_candidate + c) * out.light_words + l / 32] |= 1u << (l % 32);
                }
            }
        }
    }
    out.offsets[slot] = out.occluders.size();
    out.candidate_offsets[count] = out.candidate_occluders.size();
    out.culled = out.pairs - out.occluders.size();
}

}  // namespace rsl
