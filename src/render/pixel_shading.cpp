// Sharp shadows on coarse receivers (RenderOptions::pixel_shadows,
// docs/RENDERER.md "Per-pixel shadows"). A part's vertex colour is
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

#include "src/core/error.h"
#include "src/render/block_scratch.h"
#include "src/render/renderer.h"

namespace rsl {

namespace {

// The dimmest lights whose shares at the corners together stay below this
// fraction of the pixel's colour (sky squares low on the horizon) keep the
// corners' blend of their factor, as per vertex. Measured on the default
// frame (its ground shadow against the per-pixel truth; per vertex 11.4%)
// and on tests/render/pixel_shading_test.cpp's box (exact shape / OVDF;
// per vertex 6.5% / 6.2%): 1/64, 1/16, 1/8 and 1/4 give 9.31%, 9.31%,
// 9.30%, 9.30% and 3.9/3.3%, 3.9/3.4%, 3.9/3.4%, 3.8/3.4%, and form the
// default image in 420, 185, 125 and 96 ms (14 ms per vertex).
constexpr float kBlendedShare = 1.0f / 4.0f;

float sum_of(const Color& c) { return c.r + c.g + c.b; }

}  // namespace

// Per part shaded per pixel, during one image's formation: for each
// triangle, once its first pixel asks, the lights some occluder may shadow
// somewhere on it (bit l of `lights` words). Filled by whichever worker
// thread gets there first; a second one computing it too writes the same.
struct Renderer::TriangleLights {
    size_t words = 0;
    std::unique_ptr<std::atomic<uint8_t>[]> ready;
    std::unique_ptr<std::atomic<uint64_t>[]> masks;
};

PixelShadows parse_pixel_shadows(const std::string& name) {
    if (name == "off") return PixelShadows::Off;
    if (name == "planes") return PixelShadows::Planes;
    if (name == "all") return PixelShadows::All;
    throw_error("pixel shadows '{}': expected planes, all or off", name);
}

PartShaders Renderer::pixel_shading(const VertexColors& colors) const {
    RSL_CHECK_EQ(colors.parts.size(), scene_.parts.size());
    PartShaders shaders(scene_.parts.size());
    // The triangles and the pixels' occluders come from the culling's
    // conservative tests and its sphere tree: without culling, per vertex.
    if (!options_.occluder_culling) return shaders;
    const size_t lights = environment_squares_.size() + light_positions_.size();
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const PixelTerms& terms = pixel_terms_[p];
        if (!pixel_parts_[p] || colors.layered(p) || terms.occlusion.size() != scene_.parts[p].mesh.vertex_count() * lights)
            continue;
        const size_t triangles = scene_.parts[p].mesh.triangle_count();
        auto cache = std::make_shared<TriangleLights>();
        cache->words = (lights + 63) / 64;
        cache->ready = std::make_unique<std::atomic<uint8_t>[]>(triangles);
        cache->masks = std::make_unique<std::atomic<uint64_t>[]>(triangles * cache->words);
        shaders[p] = [this, &colors, cache](const RayHit& hit, const Vec3&) { return shade_pixel(colors, *cache, hit); };
    }
    return shaders;
}

// The lights some occluder may shadow somewhere on the triangle: the block
// culling's tests (prepare_occluder, block_unshadowed) with the triangle's
// bounding sphere as the block. Conservative: a light left out has F_l = 1
// at every point of the triangle.
void Renderer::triangle_lights(BlockScratch& s, size_t part, const uint32_t* corner, uint64_t* mask) const {
    const size_t environment = environment_squares_.size();
    const size_t lights = environment + light_positions_.size();
    for (size_t word = 0; word < (lights + 63) / 64; ++word) mask[word] = 0;
    const PartPose& pose = poses_[part];
    const TriangleMesh& mesh = scene_.parts[part].mesh;
    Vec3 p[3];
    for (int c = 0; c < 3; ++c) p[c] = Vec3(pose.transform * Vec4(mesh.positions[corner[c]], 1.0f));
    const Vec3 center = (p[0] + p[1] + p[2]) / 3.0f;
    const float radius = std::max({glm::length(p[0] - center), glm::length(p[1] - center), glm::length(p[2] - center)});
    const BoundingSphere sphere{center, radius * (1.0f + 1e-5f) + 1e-6f * (1.0f + glm::length(center))};
    ++s.stamp;
    s.pool_used = 0;
    const size_t slot_base = part * lights;
    for (size_t l = 0; l < lights; ++l) {
        bool may = false;
        for (size_t e = offsets_[slot_base + l]; e < offsets_[slot_base + l + 1] && !may; ++e) {
            const int o = occluders_[e];
            BlockScratch::BlockOccluder& b = s.occluders[size_t(o)];
            if (b.stamp != s.stamp) prepare_occluder(s, sphere, o, true);
            if (b.outside) continue;
            if (l < environment && poses_[o].uniform_scale) {
                const SquareLight& sq = environment_squares_[l];
                if (block_unshadowed(b.pole, b.spread, b.cone, sq.direction, sq.half_edge)) continue;
            }
            may = true;
        }
        if (may) mask[l / 64] |= uint64_t(1) << (l % 64);
    }
}

Color Renderer::shade_pixel(const VertexColors& colors, TriangleLights& cache, const RayHit& hit) const {
    const size_t part = size_t(hit.instance);
    const TriangleMesh& mesh = scene_.parts[part].mesh;
    const uint32_t* corner = &mesh.indices[3 * size_t(hit.triangle)];
    const float w[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
    const size_t lights = environment_squares_.size() + light_positions_.size();
    const Color blend = interpolate_vertex_colors(scene_, colors, hit);

    thread_local BlockScratch scratch;
    BlockScratch& s = scratch;
    if (s.occluders.size() != scene_.parts.size()) s.occluders.assign(scene_.parts.size(), {});
    // The triangle's lights, from the cache or computed now.
    thread_local std::vector<uint64_t> mask;
    mask.resize(cache.words);
    const size_t triangle = size_t(hit.triangle);
    std::atomic<uint64_t>* cached = &cache.masks[triangle * cache.words];
    if (cache.ready[triangle].load(std::memory_order_acquire)) {
        for (size_t word = 0; word < cache.words; ++word) mask[word] = cached[word].load(std::memory_order_relaxed);
    } else {
        triangle_lights(s, part, corner, mask.data());
        for (size_t word = 0; word < cache.words; ++word) cached[word].store(mask[word], std::memory_order_relaxed);
        cache.ready[triangle].store(1, std::memory_order_release);
    }
    bool any = false;
    for (const uint64_t word : mask) any = any || word != 0;
    if (!any) return blend;

    ++s.stamp;
    s.pool_used = 0;
    // The point and its shading frame, blended from the corners as the
    // vertices' own (shade_block).
    const PartPose& pose = poses_[part];
    Vec3 point(0), normal(0), tangent(0);
    for (int c = 0; c < 3; ++c) {
        point += w[c] * Vec3(pose.transform * Vec4(mesh.positions[corner[c]], 1.0f));
        normal += w[c] * glm::normalize(pose.normal * mesh.normals[corner[c]]);
        if (!mesh.tangents.empty()) tangent += w[c] * (pose.linear * Vec3(mesh.tangents[corner[c]]));
    }
    const Frame frame = Frame::from_normal_tangent(glm::normalize(normal), tangent);
    s.px[0] = point.x, s.py[0] = point.y, s.pz[0] = point.z;
    s.xx[0] = frame.x.x, s.xy[0] = frame.x.y, s.xz[0] = frame.x.z;
    s.yx[0] = frame.y.x, s.yy[0] = frame.y.y, s.yz[0] = frame.y.z;
    s.zx[0] = frame.z.x, s.zy[0] = frame.z.y, s.zz[0] = frame.z.z;
    const BoundingSphere block_sphere{point, 1e-6f * (1.0f + glm::length(point))};
    // The occluders whose reach holds the point, found once (a ground's
    // lists hold every part over it; a pixel is in few reaches).
    const OccluderLists& lists = frame_.occluder_lists();
    thread_local std::vector<int> found, near;
    found.clear();
    near.clear();
    lists.reach_tree.overlapping(BoundingSphere{point, 0.0f}, found);
    for (const int index : found)
        if (const int o = lists.field_parts[size_t(index)]; size_t(o) != part) near.push_back(o);

    // The dimmest of the triangle's shadowed lights, as many as together
    // hold at most kBlendedShare of the pixel's colour, are blended too.
    const PixelTerms& terms = pixel_terms_[part];
    auto share_of = [&](size_t l) {
        return std::max({sum_of(terms.unshadowed[corner[0] * lights + l]),
                         sum_of(terms.unshadowed[corner[1] * lights + l]),
                         sum_of(terms.unshadowed[corner[2] * lights + l])});
    };
    thread_local std::vector<std::pair<float, size_t>> by_share;
    by_share.clear();
    for (size_t l = 0; l < lights; ++l)
        if ((mask[l / 64] >> (l % 64)) & 1) by_share.emplace_back(share_of(l), l);
    std::sort(by_share.begin(), by_share.end());
    float blended = 0.0f;
    for (const auto& [share, l] : by_share) {
        blended += share;
        if (!(blended <= kBlendedShare * sum_of(blend))) break;
        mask[l / 64] &= ~(uint64_t(1) << (l % 64));
    }
    RenderStats counts;  // not reported: the frame's counters are the vertices'
    Color sum(0);
    for (size_t l = 0; l < lights; ++l) {
        const size_t at[3] = {corner[0] * lights + l, corner[1] * lights + l, corner[2] * lights + l};
        const Color u[3] = {terms.unshadowed[at[0]], terms.unshadowed[at[1]], terms.unshadowed[at[2]]};
        const bool shadowed = (mask[l / 64] >> (l % 64)) & 1;
        if (!shadowed || u[0] + u[1] + u[2] == Color(0)) {
            // No shadow on the triangle, or too dim to see: the corners' blend.
            for (int c = 0; c < 3; ++c) sum += w[c] * terms.occlusion[at[c]] * u[c];
            continue;
        }
        set_light(s, l, 1);
        s.queried[0] = 1;
        s.query_of[0] = 0;
        s.index[0] = 0;
        s.qx[0] = s.lpx[0], s.qy[0] = s.lpy[0], s.qh[0] = s.half[0];
        s.vis[0] = 1.0f;
        shadow_by_occluders(s, block_sphere, near, nullptr, l, 1, 1, counts);
        sum += (w[0] * u[0] + w[1] * u[1] + w[2] * u[2]) * s.vis[0];
    }
    return sum;
}

}  // namespace rsl
