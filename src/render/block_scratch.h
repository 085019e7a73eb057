#pragma once
// The CPU renderer's per-thread scratch (shade_block.cpp, pixel_shading.cpp):
// a block of up to kShadeBlock points (a part's vertices, or the points its
// pixels see), structure of arrays, never on the heap once warm. Private to
// src/render.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "src/render/ovdf_lookup.h"
#include "src/render/cpu_renderer.h"
#include "src/render/vertex_blocks.h"
#include "src/shading/culling.h"
#include "src/shading/frames.h"

namespace rsl {


// Calls visit(k), in order, for each point k < n whose byte in
// `needed_bytes` (0 or 1, zero up to the next multiple of 8 past n) is set:
// a block's (light, occluder) pair usually needs a few of its ~200 points,
// and eight flags at a time the loop skips the others without a branch
// each (one per point mispredicts).
template <typename Visit>
inline void for_each_needed(const uint8_t* needed_bytes, int n, Visit&& visit) {
    for (int first = 0; first < n; first += 8) {
        uint64_t flags;
        std::memcpy(&flags, needed_bytes + first, 8);
        for (; flags != 0; flags &= flags - 1) visit(first + std::countr_zero(flags) / 8);
    }
}

// One (light, occluder)'s vertices that need their OVDF point located, in
// the occluder's frame, and the batch's outputs (Ovdf::locate_near).
struct NearLocations {
    alignas(64) float x[kShadeBlock], y[kShadeBlock], z[kShadeBlock];
    alignas(64) float cone[kShadeBlock], occluded_area[kShadeBlock];
    alignas(64) float pole_x[kShadeBlock], pole_y[kShadeBlock], pole_z[kShadeBlock];
    alignas(64) int32_t near[kShadeBlock];
    int vertex[kShadeBlock];
};

// One occluder part's per-vertex scratch for the current block: its bounding
// cone seen from each vertex, the slab rule's box sides and the prepared
// OVDF points. Taken from a per-thread pool when a block first needs the
// occluder at vertex level, so the memory follows the occluders that
// survive block culling, not the scene's part count.
struct OccluderVertexScratch {
    // Per vertex: the part's bounding cone seen from the vertex — the unit
    // direction to its center (in the part's frame, where the lookup
    // measures the light) and the cone's plane radius
    // (OvdfLookup::unshadowed) — which alone decides most lights. Vertices
    // beyond the field's outer shell get a zero direction and radius −1,
    // which every square (h < 1) clears.
    alignas(64) float pole_x[kShadeBlock], pole_y[kShadeBlock], pole_z[kShadeBlock], cone[kShadeBlock];
    // Which side of the part's bounding box the vertex lies on along each
    // axis of the part's frame (box_sides, the slab rule).
    alignas(64) float side_x[kShadeBlock], side_y[kShadeBlock], side_z[kShadeBlock];
    // An OVDF occluder: each vertex in the part's frame, as the lookups take it.
    alignas(64) float local_x[kShadeBlock], local_y[kShadeBlock], local_z[kShadeBlock];
    // How far each vertex's OVDF lookup is located (on first need): not yet;
    // Near, its cone, blended occluded area and pole in the near_ arrays
    // (all the small-occluder rule reads, located in batches:
    // locate_near_points); or a full point in `points`.
    enum : int32_t { kUnlocated = 0, kNear = 1, kPoint = 2 };
    alignas(64) int32_t located[kShadeBlock];  // 32-bit: the small-occluder loop gathers it
    alignas(64) float near_cone[kShadeBlock], near_area[kShadeBlock];
    alignas(64) float near_pole_x[kShadeBlock], near_pole_y[kShadeBlock], near_pole_z[kShadeBlock];
    // The light-independent half of the OVDF lookup, located when a light
    // needs the tables or the vertex lies within the bounding sphere and
    // completed with its terms when a light needs them, and the terms the
    // points use (their own, so that a pool that grows never moves them).
    OvdfPoint points[kShadeBlock];
    OvdfTerm terms[kShadeBlock * OvdfPoint::kMaxTerms];
    int terms_used = 0;
    // An occluder of exact shape (occluder_shape.h): each vertex's point and
    // shading frame in the shape's coordinates, and whether it lies within
    // the field's reach (beyond it the part shadows nothing, as its OVDF).
    Vec3 shape_point[kShadeBlock];
    shading::LocalFrame shape_frame[kShadeBlock];
    bool in_reach[kShadeBlock];
};

using shading::BlockSpread;
using shading::block_spread;
using shading::block_unshadowed;

// Per-thread scratch of one block (about 40 KB plus the occluder pool, never
// on the heap once warm).
struct CpuRenderer::BlockScratch {
    // The part's vertex at each point (shade_block; the renderer's block order).
    int vertex[kShadeBlock];
    // Per point, parts with highlights per pixel: its rim view floor (brdf_queries).
    alignas(64) float view_floor[kShadeBlock];
    // World positions and shading frames (x = tangent, y = bitangent, z = normal).
    alignas(64) float px[kShadeBlock], py[kShadeBlock], pz[kShadeBlock];
    alignas(64) float xx[kShadeBlock], xy[kShadeBlock], xz[kShadeBlock];
    alignas(64) float yx[kShadeBlock], yy[kShadeBlock], yz[kShadeBlock];
    alignas(64) float zx[kShadeBlock], zy[kShadeBlock], zz[kShadeBlock];
    // View in the local frame, and the view-aligned rotation (cos φ_o, sin φ_o).
    alignas(64) float vx[kShadeBlock], vy[kShadeBlock], vz[kShadeBlock], view_cos[kShadeBlock], view_sin[kShadeBlock];
    alignas(64) float r[kShadeBlock], g[kShadeBlock], b[kShadeBlock];  // colour sums (textured parts: the diffuse layer)
    alignas(64) float sr[kShadeBlock], sg[kShadeBlock], sb[kShadeBlock];  // textured parts: the specular layer's sums
    // The current light per vertex (local lights vary per vertex).
    alignas(64) float dx[kShadeBlock], dy[kShadeBlock], dz[kShadeBlock], half[kShadeBlock], ir[kShadeBlock], ig[kShadeBlock], ib[kShadeBlock];
    // Local plane point of the light's center and the light's local z.
    alignas(64) float lpx[kShadeBlock], lpy[kShadeBlock], lz[kShadeBlock];
    // The exact diffuse light (RenderOptions::exact_diffuse_light): per point
    // its gain g (shading/diffuse_light.h), and per slot 1 for an environment
    // light, 0 for a local one; `gains` false: none this block.
    alignas(64) float gain_r[kShadeBlock], gain_g[kShadeBlock], gain_b[kShadeBlock];
    alignas(64) float environment_slot[kShadeBlock];
    bool gains = false;
    // With gains, per environment light l and point k, c_l at k:
    // cosines[l·kShadeBlock + k] (sized at the first block); light_cosines
    // points at the current light's row (set_light), null where brdf_queries
    // computes c itself (a pixel's lights, local lights).
    std::vector<float> cosines;
    const float* light_cosines = nullptr;
    alignas(64) int32_t crossing[kShadeBlock];
    // Per point the skinned segment whose OVDF it leaves out (-1: none):
    // a seam vertex's neighbour (CpuRenderer::seam_partners_); -1 at pixels.
    alignas(64) int32_t partner[kShadeBlock];
    bool any_partner = false;  // some point of the block has one
    // A part whose roughness and metallic vary per point (pbr_basis.h): per
    // point its weights on D, S(0.04, ·) and S(1, ·) and its two roughness
    // levels; the levels any point uses; one basis table's averages.
    bool pbr = false;
    alignas(64) float pbr_dr[kShadeBlock], pbr_dg[kShadeBlock], pbr_db[kShadeBlock];
    alignas(64) float pbr_er[kShadeBlock], pbr_eg[kShadeBlock], pbr_eb[kShadeBlock];
    alignas(64) float pbr_mr[kShadeBlock], pbr_mg[kShadeBlock], pbr_mb[kShadeBlock];
    alignas(64) int32_t pbr_level[kShadeBlock];
    alignas(64) float pbr_upper[kShadeBlock];
    int pbr_first = 0, pbr_last = -1;
    bool pbr_metal = false;
    alignas(64) float tr[kShadeBlock], tg[kShadeBlock], tb[kShadeBlock];
    // Compacted queries.
    int index[kShadeBlock];
    int query_vertex[kShadeBlock];  // the vertex of each query (shade_block)
    alignas(64) float qx[kShadeBlock], qy[kShadeBlock], tx[kShadeBlock], ty[kShadeBlock], qh[kShadeBlock];
    alignas(64) float qvx[kShadeBlock], qvy[kShadeBlock], qvz[kShadeBlock];
    alignas(64) float br[kShadeBlock], bg[kShadeBlock], bb[kShadeBlock], vis[kShadeBlock];
    alignas(64) float unshadowed_vis[kShadeBlock];  // parts shaded per pixel: vis before the other parts' shadows
    alignas(64) float spr[kShadeBlock], spg[kShadeBlock], spb[kShadeBlock];  // the specular table's averages
    // Per vertex: whether the current light has a query for it, and which
    // (valid where queried); whether the current (light, occluder) needs a
    // lookup, 0 or 1 (32-bit: GCC 12 vectorizes no loop that computes a
    // byte from floats), and the same packed in bytes for the lookup loop.
    alignas(64) int32_t queried[kShadeBlock];
    int query_of[kShadeBlock];
    alignas(64) int32_t needed[kShadeBlock];
    alignas(64) uint8_t needed_bytes[kShadeBlock];
    // Ray-traced visibility (options.exact_visibility): per query, whether it
    // needs no rays, and its visible fraction.
    alignas(64) bool skip[kShadeBlock];
    alignas(64) float exact[kShadeBlock];
    // One (light, occluder)'s vertices to locate (ovdf_factors.cpp).
    NearLocations near;
    // One (light, occluder)'s OVDF lookups (ovdf_factors.cpp), listed so
    // that the small-occluder rule — a lens area: two arccos polynomials and
    // a square root, most lookups in a scene of many parts — runs in one
    // vectorized loop: each query's vertex, index and half-edge, the light's
    // direction in the part's frame, and whether the rule alone decides it
    // and its value.
    struct OvdfQueries {
        int vertex[kShadeBlock], query[kShadeBlock];
        alignas(64) float half_edge[kShadeBlock], dir_x[kShadeBlock], dir_y[kShadeBlock], dir_z[kShadeBlock];
        alignas(64) int32_t small[kShadeBlock];
        alignas(64) float fraction[kShadeBlock];
    } ovdf;

    // Per occluder part (sized to the scene on first use): what the block
    // knows of it, valid while `stamp` equals the block's. The bounding cone
    // as the whole block sees it: the direction from the block's center to
    // the part's, how far any vertex's pole can turn from it (with a margin), and
    // the largest cone plane radius of any vertex (negative: some vertex may
    // lie in the bounding sphere).
    struct BlockOccluder {
        uint64_t stamp = 0;
        bool outside = false;  // the whole block lies beyond the occluder's outer shell
        Vec3 pole{0};
        BlockSpread spread{1.0f, 0.0f};
        float cone = -1;
        OccluderVertexScratch* vertices = nullptr;  // null until the block needs it at vertex level
    };
    std::vector<BlockOccluder> occluders;
    uint64_t stamp = 0;  // the current block's
    std::vector<std::unique_ptr<OccluderVertexScratch>> pool;
    size_t pool_used = 0;  // of the pool, by the current block
};

}  // namespace rsl
