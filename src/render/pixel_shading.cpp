// Sharp shadows on coarse receivers (RenderOptions::pixel_shadows,
// docs/design/RENDERER.md "Per-pixel shadows"). A part's vertex colour is
//
//   Σ_l U_l(v) · F_l(v),  U_l = 2r²I × BRDF average × SVDF average,
//                         F_l = Π_occluders OVDF average,
//
// and F_l is a field in space: it can be evaluated at any point, not only at
// vertices. Where the vertices are coarser than the shadows falling on the
// part, the blend of the corners' colours draws a sharp shadow edge as a
// comb, or misses a small shadow between them. Image formation instead takes
// Σ_l Ū_l · F_l(x) at the point x each pixel sees, Ū_l the corners' U_l
// blended, for the lights that some occluder may shadow somewhere on the
// pixel's triangle (the block culling's conservative tests, with the
// triangle as the block); for the others F_l = 1 on the whole triangle and
// the blend is exact.
//
// A pixel is a block of one point for the shading kernel (shade_block.cpp):
// the same light squares, occluder lists, culling and lookups as the vertices.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>

#include "src/core/error.h"
#include "src/render/block_scratch.h"
#include "src/render/cpu_renderer.h"

namespace rsl {

namespace {

// The dimmest lights whose shares at the corners together stay below this
// fraction of the pixel's colour (sky squares low on the horizon) keep the
// corners' blend of their factor, as per vertex: the image's error is the
// same from 1/64 to 1/4, and 1/4 forms it four times faster
// (docs/journal/parameter-sweeps.md).
constexpr float kBlendedShare = 1.0f / 4.0f;

float sum_of(const Color& c) { return c.r + c.g + c.b; }

}  // namespace

// The occluders that may shadow a triangle, per light: light l's are
// ids[first[l] .. first[l + 1]). A pixel of the triangle looks up these
// alone, not every part whose reach holds it: in a dense scene (128 parts
// within reach of each other) that was 128 cone tests per pixel and light.
// Built in a thread's scratch (`first`, `ids`), kept in one block per
// triangle (`packed`: the lights + 1 offsets, then the ids), and none for a
// triangle that no occluder may shadow.
struct CpuRenderer::TriangleOccluders {
    std::vector<uint32_t> first;
    std::vector<int> ids;
    std::span<const int> of(size_t l) const {
        return std::span<const int>(ids).subspan(first[l], first[l + 1] - first[l]);
    }
};
// Per part shaded per pixel, during one image's formation: for each
// triangle, once its first pixel asks, the lights some occluder may shadow
// somewhere on it (bit l of `lights` words) and those occluders. The first
// worker thread to claim a triangle fills them; another that finds it being
// filled computes its own copy.
struct CpuRenderer::TriangleLights {
    struct PackedOccluders {
        std::unique_ptr<int[]> packed;
        std::span<const int> of(size_t l, size_t lights) const {
            const int* ids = packed.get() + lights + 1;
            return std::span<const int>(ids + packed[l], ids + packed[l + 1]);
        }
    };
    static constexpr uint8_t kEmpty = 0, kReady = 1, kFilling = 2;
    size_t words = 0;
    std::unique_ptr<std::atomic<uint8_t>[]> state;
    std::unique_ptr<uint64_t[]> masks;
    std::unique_ptr<PackedOccluders[]> occluders;
};

// A vertex v whose normal is within δ_v of every normal it shares a
// triangle with: when its view cosine is below −sin δ_v, every such
// neighbour faces away too, and no pixel that sees the camera side blends
// its terms. The margin covers the view's change from vertex to vertex
// (perspective) and the interpolated normals' own spread.
std::vector<float> CpuRenderer::rim_view_floors(const TriangleMesh& mesh) {
    constexpr float kMargin = 0.05f;
    std::vector<float> min_cosine(mesh.vertex_count(), 1.0f);  // of the angle to the neighbours' normals
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t* corner = &mesh.indices[3 * t];
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                const float c = glm::dot(mesh.normals[corner[a]], mesh.normals[corner[b]]);
                min_cosine[corner[a]] = std::min(min_cosine[corner[a]], c);
            }
    }
    std::vector<float> floors(mesh.vertex_count());
    for (size_t v = 0; v < floors.size(); ++v) {
        const float c = std::clamp(min_cosine[v], -1.0f, 1.0f);
        const float sine = c > 0.0f ? std::sqrt(1.0f - c * c) : 1.0f;  // δ ≥ 90°: any view
        floors[v] = -sine - kMargin;
    }
    return floors;
}

PixelShadows parse_pixel_shadows(const std::string& name) {
    if (name == "off") return PixelShadows::Off;
    if (name == "planes") return PixelShadows::Planes;
    if (name == "all") return PixelShadows::All;
    throw_error("pixel shadows '{}': expected planes, all or off", name);
}

Image CpuRenderer::backend_image(const VertexColors& colors, const PinholeCamera& camera,
                                 const ImageFormationOptions& options) {
    if (!shaded_current_frame_) throw_error("form_image: the image needs a shade() of the current frame");
    if (!terms_kept_ && (options_.pixel_highlights || std::find(pixel_parts_.begin(), pixel_parts_.end(), 1) !=
                                                          pixel_parts_.end()))
        throw_error("form_image: the last shade() kept no terms for the parts shaded per pixel "
                    "(keep_image_terms(true) before it)");
    if (!posed_)
        posed_ = std::make_unique<PosedScene>(scene_, time_);
    else
        posed_->set_time(time_);
    return rsl::form_image(*posed_, camera, colors, options, pixel_shading(colors, *posed_));
}

PartShaders CpuRenderer::pixel_shading(const VertexColors& emitting_colors, const PosedScene& posed) const {
    RSL_CHECK_EQ(emitting_colors.parts.size(), scene_.parts.size());
    // The shaders sum what the surfaces reflect; form_image adds the emission at each pixel.
    std::shared_ptr<const VertexColors> reflected;
    if (any_emission(scene_, emitting_colors))
        reflected = std::make_shared<const VertexColors>(reflected_colors(scene_, emitting_colors));
    const VertexColors& colors = reflected ? *reflected : emitting_colors;
    PartShaders shaders(scene_.parts.size());
    const size_t lights = environment_squares_.size() + light_positions_.size();
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const PixelTerms& terms = pixel_terms_[p];
        const size_t pairs = scene_.parts[p].mesh.vertex_count() * lights;
        if (terms.occlusion.size() != pairs) continue;  // not shaded per pixel in the last frame
        // A textured part: per-pixel shadows with both layers kept, and its texture.
        const bool layered = colors.layered(p);
        if (layered && (terms.unshadowed_specular.size() != pairs || !layer_texture(scene_, colors, p))) continue;
        // Shadows per pixel need the culling's conservative tests and its
        // sphere tree (to find the triangles and the occluders).
        std::shared_ptr<TriangleLights> cache;
        if (terms.unshadowed.size() == pairs && options_.occluder_culling) {
            const size_t triangles = scene_.parts[p].mesh.triangle_count();
            cache = std::make_shared<TriangleLights>();
            cache->words = (lights + 63) / 64;
            cache->state = std::make_unique<std::atomic<uint8_t>[]>(triangles);
            cache->masks = std::make_unique<uint64_t[]>(triangles * cache->words);
            cache->occluders = std::make_unique<TriangleLights::PackedOccluders[]>(triangles);
        }
        if (!cache && (layered || terms.self_visibility.size() != pairs)) continue;
        const VertexColors* source = &colors;  // `reflected`, held by the shader, or the caller's
        shaders[p] = [this, source, reflected, &posed, cache](const RayHit& hit, const Vec3& direction) {
            return shade_pixel(*source, posed, cache.get(), hit, direction);
        };
    }
    return shaders;
}

// The other parts whose occluder field reaches `sphere` (from the frame's
// sphere tree over the reaches): a ground's per-light lists hold every part
// over it, a triangle lies in few reaches.
void CpuRenderer::occluders_near(const BoundingSphere& sphere, size_t part, std::vector<int>& out) const {
    const OccluderLists& lists = frame_.occluder_lists();
    thread_local std::vector<int> found;
    found.clear();
    out.clear();
    lists.reach_tree.overlapping(sphere, found);
    for (const int index : found)
        if (const int o = lists.field_parts[size_t(index)]; size_t(o) != part) out.push_back(o);
}

// The lights some occluder may shadow somewhere on the triangle, and per
// light those occluders: the block culling's tests (block_may_be_shadowed)
// with the triangle's bounding sphere as the block. Conservative: a light
// left out has F_l = 1 at every point of the triangle, and so has the
// factor of an occluder left out of a light's list.
void CpuRenderer::triangle_lights(BlockScratch& s, size_t part, const uint32_t* corner, uint64_t* mask,
                               TriangleOccluders& occluders) const {
    const size_t lights = environment_squares_.size() + light_positions_.size();
    for (size_t word = 0; word < (lights + 63) / 64; ++word) mask[word] = 0;
    const PartPose& pose = poses_[part];
    const TriangleMesh& mesh = scene_.parts[part].mesh;
    Vec3 p[3];
    const PosedVertices* skinned = frame_.skinned(part);  // as posed this frame (src/core/skinning.h)
    const std::vector<Vec3>& positions = skinned ? skinned->positions : mesh.positions;
    for (int c = 0; c < 3; ++c) p[c] = Vec3(pose.transform * Vec4(positions[corner[c]], 1.0f));
    const Vec3 center = (p[0] + p[1] + p[2]) / 3.0f;
    const float radius = std::max({glm::length(p[0] - center), glm::length(p[1] - center), glm::length(p[2] - center)});
    const BoundingSphere sphere{center, radius * (1.0f + 1e-5f) + 1e-6f * (1.0f + glm::length(center))};
    ++s.stamp;
    s.pool_used = 0;
    // The part's per-light lists (their part-level light test prunes the
    // most), each entry looked at only when its reach meets the triangle.
    thread_local std::vector<int> near;
    thread_local std::vector<uint64_t> near_stamp;
    occluders_near(sphere, part, near);
    near_stamp.resize(scene_.parts.size(), 0);
    for (const int o : near) near_stamp[size_t(o)] = s.stamp;
    const size_t slot_base = part * lights;
    occluders.first.assign(lights + 1, 0);
    occluders.ids.clear();
    for (size_t l = 0; l < lights; ++l) {
        occluders.first[l] = uint32_t(occluders.ids.size());
        bool may = false;
        for (size_t e = offsets_[slot_base + l]; e < offsets_[slot_base + l + 1] && !may; ++e)
            may = near_stamp[size_t(occluders_[e])] == s.stamp &&
                  block_may_be_shadowed(s, sphere, occluders_[e], occluder_growth_[e], l);
        if (!may) continue;
        mask[l / 64] |= uint64_t(1) << (l % 64);
        // The light's occluders among the near ones, by the tests a pixel
        // makes (no part-level light test): a superset of any pixel's.
        for (const int o : near)
            if (block_may_be_shadowed(s, sphere, o, -1.0f, l)) occluders.ids.push_back(o);
    }
    occluders.first[lights] = uint32_t(occluders.ids.size());
}

// A pixel's shadowed lights: bit l of `mask` when some occluder may shadow
// light l on the pixel's triangle, and per light those occluders (the
// cache's packed lists, or `built` for a triangle another thread is filling).
struct CpuRenderer::PixelOccluders {
    std::vector<uint64_t>& mask;
    const TriangleLights::PackedOccluders* packed = nullptr;
    TriangleOccluders& built;
    size_t lights = 0;
    BoundingSphere point_sphere;  // the pixel's point as a block of one
    RenderStats counts;           // not reported: the frame's counters are the vertices'
    bool shadowed(size_t l) const { return (mask[l / 64] >> (l % 64)) & 1; }
    std::span<const int> of(size_t l) const { return packed ? packed->of(l, lights) : built.of(l); }
};

Color CpuRenderer::shade_pixel(const VertexColors& colors, const PosedScene& posed, TriangleLights* cache,
                             const RayHit& hit, const Vec3& ray_direction) const {
    const size_t part = size_t(hit.instance);
    const TriangleMesh& mesh = scene_.parts[part].mesh;
    const uint32_t* corner = &mesh.indices[3 * size_t(hit.triangle)];
    const float w[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
    const size_t lights = environment_squares_.size() + light_positions_.size();
    const PixelTerms& terms = pixel_terms_[part];
    const bool highlights = !terms.self_visibility.empty();
    // A textured part: the diffuse layer times the texture, plus the specular layer.
    const Texture* texture = colors.layered(part) ? layer_texture(scene_, colors, part) : nullptr;
    const Color blend = texture ? interpolate_layered_colors(scene_, colors, *texture, hit)
                                : interpolate_vertex_colors(scene_, colors, hit);

    thread_local BlockScratch scratch;
    BlockScratch& s = scratch;
    if (s.occluders.size() != scene_.parts.size()) s.occluders.assign(scene_.parts.size(), {});
    thread_local std::vector<uint64_t> mask;
    mask.assign((lights + 63) / 64, 0);
    thread_local TriangleOccluders built;
    PixelOccluders occluders{mask, nullptr, built, lights, {}, {}};
    if (cache) {
        triangle_shadowed_lights(s, *cache, part, size_t(hit.triangle), occluders);
        blend_dimmest_lights(terms, corner, texture != nullptr, sum_of(blend), occluders);
    }
    bool any = false;
    for (const uint64_t word : mask) any = any || word != 0;
    if (!any && !highlights) return blend;

    ++s.stamp;
    s.pool_used = 0;
    // The point and its shading frame, as the per-pixel truth takes them.
    const SurfacePoint x = posed.hit_point(hit, ray_direction);
    set_point(s, 0, x.position, x.frame);
    s.partner[0] = -1, s.any_partner = false;  // a pixel takes every occluder's shadow (shade_block.cpp, seam partners)
    occluders.point_sphere = BoundingSphere{x.position, 1e-6f * (1.0f + glm::length(x.position))};
    if (highlights) return pixel_highlights(s, occluders, part, corner, w);
    return pixel_shadows(s, occluders, terms, corner, w, texture, hit);
}

// The triangle's shadowed lights into `o.mask`, from the cache or computed
// now; `o.packed` the cache's occluder lists, or null when `o.built` holds them.
void CpuRenderer::triangle_shadowed_lights(BlockScratch& s, TriangleLights& cache, size_t part, size_t triangle,
                                           PixelOccluders& o) const {
    const uint32_t* corner = &scene_.parts[part].mesh.indices[3 * triangle];
    uint64_t* cached = &cache.masks[triangle * cache.words];
    std::atomic<uint8_t>& state = cache.state[triangle];
    uint8_t seen = state.load(std::memory_order_acquire);
    if (seen == TriangleLights::kReady) {
        std::copy(cached, cached + cache.words, o.mask.begin());
        o.packed = &cache.occluders[triangle];
        return;
    }
    triangle_lights(s, part, corner, o.mask.data(), o.built);
    // Kept when this thread claims the triangle first; else (another
    // thread is filling it) used from `built` for this pixel alone.
    if (seen == TriangleLights::kEmpty &&
        state.compare_exchange_strong(seen, TriangleLights::kFilling, std::memory_order_acquire)) {
        std::copy(o.mask.begin(), o.mask.end(), cached);
        if (!o.built.ids.empty()) {
            TriangleLights::PackedOccluders& keep = cache.occluders[triangle];
            keep.packed = std::make_unique<int[]>(o.lights + 1 + o.built.ids.size());
            std::copy(o.built.first.begin(), o.built.first.end(), keep.packed.get());
            std::copy(o.built.ids.begin(), o.built.ids.end(), keep.packed.get() + o.lights + 1);
        }
        state.store(TriangleLights::kReady, std::memory_order_release);
    }
}

// The dimmest of the triangle's shadowed lights, as many as together hold at
// most kBlendedShare of the pixel's colour (`pixel_sum`), leave the mask:
// they keep the corners' blend of their factor.
void CpuRenderer::blend_dimmest_lights(const PixelTerms& terms, const uint32_t* corner, bool textured,
                                       float pixel_sum, PixelOccluders& o) {
    auto share_of = [&](size_t l) {
        float share = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const size_t at = corner[c] * o.lights + l;
            share = std::max(share, sum_of(terms.unshadowed[at]) + (textured ? sum_of(terms.unshadowed_specular[at]) : 0.0f));
        }
        return share;
    };
    thread_local std::vector<std::pair<float, size_t>> by_share;
    by_share.clear();
    for (size_t l = 0; l < o.lights; ++l)
        if (o.shadowed(l)) by_share.emplace_back(share_of(l), l);
    std::sort(by_share.begin(), by_share.end());
    float blended = 0.0f;
    for (const auto& [share, l] : by_share) {
        blended += share;
        if (!(blended <= kBlendedShare * pixel_sum)) break;
        o.mask[l / 64] &= ~(uint64_t(1) << (l % 64));
    }
}

// The other parts' factor of light l at the pixel's point (set_point'ed in
// slot 0), from the triangle's occluders of that light.
float CpuRenderer::pixel_occlusion(BlockScratch& s, PixelOccluders& o, size_t l) const {
    set_light(s, l, 1);
    s.queried[0] = 1;
    s.query_of[0] = 0;
    s.index[0] = 0;
    s.qx[0] = s.lpx[0], s.qy[0] = s.lpy[0], s.qh[0] = s.half[0];
    s.vis[0] = 1.0f;
    shadow_by_occluders(s, o.point_sphere, o.of(l), nullptr, l, 1, 1, o.counts);
    return s.vis[0];
}

// Highlights per pixel: Σ I_l · B_l(x) · SVDF_l blended · F_l, the BRDF at
// the pixel's point, all the lights' BRDF averages in one batch (slot l =
// light l); F_l at the point for the shadowed lights, else the corners' blend.
Color CpuRenderer::pixel_highlights(BlockScratch& s, PixelOccluders& o, size_t part, const uint32_t* corner,
                                    const float w[3]) const {
    const size_t lights = o.lights;
    const PixelTerms& terms = pixel_terms_[part];
    RSL_CHECK(lights <= size_t(kShadeBlock));  // CpuRenderer::shade keeps no highlight terms for more
    set_lights_at_point(s, lights);
    // A part varying per point: the texture's roughness and metallic at the pixel.
    s.pbr = !part_pbr_points_[part].empty();
    if (s.pbr) {
        const std::vector<Vec2>& uv = scene_.parts[part].mesh.texcoords;
        const PbrPoint point = pbr_point(library_.desc(library_.part_material(int(part))),
                                         w[0] * uv[corner[0]] + w[1] * uv[corner[1]] + w[2] * uv[corner[2]]);
        s.pbr_first = kPbrLevels, s.pbr_last = -1, s.pbr_metal = false;
        for (size_t l = 0; l < lights; ++l) set_pbr_point(s, int(l), part_pbr_base_[part], point);
    }
    diffuse_light_gains(s, int(part), 1);  // every slot holds the pixel's point
    for (size_t l = 1; l < lights; ++l)
        s.gain_r[l] = s.gain_r[0], s.gain_g[l] = s.gain_g[0], s.gain_b[l] = s.gain_b[0];
    const int m = brdf_queries(s, *part_tables_[part], nullptr, int(lights));
    // An enclosed corner's self-visibility is the inside's: the seen point is outside.
    float ws[3] = {w[0], w[1], w[2]};
    if (const std::vector<uint8_t>& enclosed = enclosed_vertices_[part]; !enclosed.empty()) {
        float open = 0.0f;
        for (int c = 0; c < 3; ++c) open += enclosed[corner[c]] ? 0.0f : w[c];
        if (open > 0.0f)
            for (int c = 0; c < 3; ++c) ws[c] = enclosed[corner[c]] ? 0.0f : w[c] / open;
    }
    Color sum(0);
    thread_local std::vector<std::pair<size_t, Color>> shadowed_lights;
    shadowed_lights.clear();
    for (int i = 0; i < m; ++i) {
        const size_t l = size_t(s.index[i]);
        const size_t at[3] = {corner[0] * lights + l, corner[1] * lights + l, corner[2] * lights + l};
        const float self = ws[0] * terms.self_visibility[at[0]] + ws[1] * terms.self_visibility[at[1]] +
                           ws[2] * terms.self_visibility[at[2]];
        if (!(self > 0.0f)) continue;  // no share at any corner, or a light switched off
        const Color unshadowed = self * Color(s.ir[l] * s.br[i], s.ig[l] * s.bg[i], s.ib[l] * s.bb[i]);
        if (o.shadowed(l)) {
            shadowed_lights.emplace_back(l, unshadowed);
            continue;
        }
        sum += (w[0] * terms.occlusion[at[0]] + w[1] * terms.occlusion[at[1]] + w[2] * terms.occlusion[at[2]]) *
               unshadowed;
    }
    for (const auto& [l, unshadowed] : shadowed_lights)  // they reuse slot 0
        sum += pixel_occlusion(s, o, l) * unshadowed;
    return sum;
}

// Shadows per pixel: Σ Ū_l · F_l(x), the corners' blend Ū_l of each light's
// share; F_l at the point for the shadowed lights, else the corners' blend.
Color CpuRenderer::pixel_shadows(BlockScratch& s, PixelOccluders& o, const PixelTerms& terms, const uint32_t* corner,
                                 const float w[3], const Texture* texture, const RayHit& hit) const {
    const size_t lights = o.lights;
    Color sum(0), specular_sum(0);  // specular: a textured part's specular layer
    for (size_t l = 0; l < lights; ++l) {
        const size_t at[3] = {corner[0] * lights + l, corner[1] * lights + l, corner[2] * lights + l};
        const Color u[3] = {terms.unshadowed[at[0]], terms.unshadowed[at[1]], terms.unshadowed[at[2]]};
        const Color v[3] = {texture ? terms.unshadowed_specular[at[0]] : Color(0),
                            texture ? terms.unshadowed_specular[at[1]] : Color(0),
                            texture ? terms.unshadowed_specular[at[2]] : Color(0)};
        if (!o.shadowed(l) || u[0] + u[1] + u[2] + v[0] + v[1] + v[2] == Color(0)) {
            // No shadow on the triangle, or too dim to see: the corners' blend.
            for (int c = 0; c < 3; ++c) {
                sum += w[c] * terms.occlusion[at[c]] * u[c];
                specular_sum += w[c] * terms.occlusion[at[c]] * v[c];
            }
            continue;
        }
        const float occlusion = pixel_occlusion(s, o, l);
        sum += (w[0] * u[0] + w[1] * u[1] + w[2] * u[2]) * occlusion;
        specular_sum += (w[0] * v[0] + w[1] * v[1] + w[2] * v[2]) * occlusion;
    }
    if (texture) return sum * texture->lookup(interpolate_texcoords(scene_, hit)) + specular_sum;
    return sum;
}

}  // namespace rsl
