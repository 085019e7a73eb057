// The per-block shading kernel of the CPU renderer: one light at a time over
// all the vertices of a block, structure of arrays, no allocation.
//
// For each light the block's vertices are first projected into their local
// plane (a branch-free loop the compiler vectorizes), then the vertices whose
// view is above the horizon and whose square reaches the upper hemisphere are
// compacted into query arrays, looked up in one BRDF batch, multiplied by the
// self and occluder visibility, and scattered back into the colour sums.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "src/core/error.h"
#include "src/render/exact_visibility.h"
#include "src/render/block_scratch.h"
#include "src/render/ovdf_lookup.h"
#include "src/render/cpu_renderer.h"
#include "src/shading/diffuse_light.h"
#include "src/shading/frames.h"
#include "src/shading/squares.h"
#include "src/shading/ovdf_tables.h"
#include "src/shading/shapes.h"

namespace rsl {

// Per block and occluder, before its first lookup: whether the block lies
// beyond the field's outer shell, and the part's bounding cone as the whole
// block sees it (O(1): from the block's bounding sphere).
void CpuRenderer::prepare_occluder(BlockScratch& s, const BoundingSphere& block_sphere, int o, bool culling) const {
    BlockScratch::BlockOccluder& b = s.occluders[size_t(o)];
    b.stamp = s.stamp;
    b.outside = false;
    b.cone = -1.0f;
    b.vertices = nullptr;
    if (!culling) return;
    const PartPose& occluder = poses_[o];
    const BoundingSphere reach = transform_sphere(occluder.transform, local_reach_[o]);
    b.outside = beyond_reach(block_sphere, reach);
    const OvdfLookup* fast = fast_lookups_[o].get();
    if (b.outside || !fast) return;
    // Every vertex is at distance ≥ d − r from the part's center, so its cone
    // radius is at most the cone at d − r (it grows as the distance shrinks),
    // and its pole is within asin(r / d) of the block center's.
    const Ovdf& field = fast->field();
    const BoundingSphere part = transform_sphere(occluder.transform, BoundingSphere{field.center, field.radius});
    const Vec3 to_part = part.center - block_sphere.center;
    const float d = glm::length(to_part);
    if (!(d - block_sphere.radius > part.radius)) return;  // a vertex may lie in the bounding sphere: no cone
    b.pole = to_part / d;
    b.spread = block_spread(block_sphere.radius, d);
    b.cone = ovdf_zoom(d - block_sphere.radius, part.radius).cone;
}


// Each vertex's bounding cone of the part and its box sides, before the
// first light that the block-level tests do not decide.
OccluderVertexScratch& CpuRenderer::prepare_occluder_vertices(BlockScratch& s, int o, int n, bool culling) const {
    if (s.pool_used == s.pool.size()) s.pool.push_back(std::make_unique<OccluderVertexScratch>());  // warm-up only
    OccluderVertexScratch& v = *s.pool[s.pool_used++];
    s.occluders[size_t(o)].vertices = &v;
    v.terms_used = 0;
    for (int k = 0; k < n; ++k) v.located[k] = OccluderVertexScratch::kUnlocated;
    // In the occluder's frame, structure of arrays so that the loop
    // vectorizes: the box sides (the slab rule), and as OvdfLookup::prepare
    // the pole and the cone (ratios d/R are the same in the world).
    const OvdfLookup* fast = fast_lookups_[o].get();
    const Bounds box = local_boxes_[o];  // copies, as m below
    const bool cones = fast && culling;
    const Vec3 center = fast ? fast->field().center : Vec3(0);
    const float radius = fast ? fast->field().radius : 0.0f;
    const float outer = fast ? fast->field().shell_radius(fast->field().params.shells - 1) : 0.0f;
    const Mat4 m = poses_[o].inverse;  // a copy: the scratch's float stores could alias a reference
    // The block's and the occluder's scratch never overlap; without saying
    // so GCC would need more run-time alias checks than it makes, and not
    // vectorize.
    RSL_VECTORIZE_NO_ALIAS
    for (int k = 0; k < n; ++k) {
        const float x = m[0][0] * s.px[k] + m[1][0] * s.py[k] + m[2][0] * s.pz[k] + m[3][0];
        const float y = m[0][1] * s.px[k] + m[1][1] * s.py[k] + m[2][1] * s.pz[k] + m[3][1];
        const float z = m[0][2] * s.px[k] + m[1][2] * s.py[k] + m[2][2] * s.pz[k] + m[3][2];
        v.side_x[k] = box_side(x, box.lo.x, box.hi.x);
        v.side_y[k] = box_side(y, box.lo.y, box.hi.y);
        v.side_z[k] = box_side(z, box.lo.z, box.hi.z);
        // As glm's m * vec4(p, 1), which the lookups took before (the same sums).
        v.local_x[k] = (m[0][0] * s.px[k] + m[1][0] * s.py[k]) + (m[2][0] * s.pz[k] + m[3][0]);
        v.local_y[k] = (m[0][1] * s.px[k] + m[1][1] * s.py[k]) + (m[2][1] * s.pz[k] + m[3][1]);
        v.local_z[k] = (m[0][2] * s.px[k] + m[1][2] * s.py[k]) + (m[2][2] * s.pz[k] + m[3][2]);
        const float vx = x - center.x, vy = y - center.y, vz = z - center.z;
        const float d = std::sqrt(vx * vx + vy * vy + vz * vz);
        const bool inside = d < outer;
        const float inv = inside && d > 0.0f ? -1.0f / d : 0.0f;  // the pole points towards the center
        v.pole_x[k] = vx * inv, v.pole_y[k] = vy * inv, v.pole_z[k] = vz * inv;
        const float cone = d <= radius ? kOvdfNoCone : shading::ovdf_cone_radius(d, radius);  // ovdf_zoom's, branch-free
        v.cone[k] = inside ? cone : -1.0f;
    }
    if (!cones)  // no culling, or not an OVDF: every light is looked up
        for (int k = 0; k < n; ++k) v.cone[k] = kOvdfNoCone;
    const OccluderShape& shape = shapes_[size_t(o)];
    if (shape.kind != shading::kShapeNone) {
        const BoundingSphere& reach = local_reach_[size_t(o)];
        const Mat3& il = poses_[o].inverse_linear;
        for (int k = 0; k < n; ++k) {
            const Vec3 local = Vec3(m * Vec4(s.px[k], s.py[k], s.pz[k], 1.0f));
            v.in_reach[k] = glm::length(local - reach.center) < reach.radius;
            v.shape_point[k] = shape.to_shape(local);
            shading::LocalFrame& frame = v.shape_frame[k];
            frame.x = shape.direction_to_shape(il * Vec3(s.xx[k], s.xy[k], s.xz[k]));
            frame.y = shape.direction_to_shape(il * Vec3(s.yx[k], s.yy[k], s.yz[k]));
            frame.z = shape.direction_to_shape(il * Vec3(s.zx[k], s.zy[k], s.zz[k]));
        }
    }
    return v;
}

// One occluder's factor for the block's queries of light l: the masks (its
// bounding cone, the slab rule) and then the OVDF lookups, multiplied into
// s.vis. Out of line so that the lookups inline into its loop.
void CpuRenderer::occluder_factors(BlockScratch& s, OccluderVertexScratch& v, int l, int o, int n, int m,
                                RenderStats& counts) const {
    const PartPose& occluder = poses_[o];
    const bool is_environment = size_t(l) < environment_squares_.size();
    const OvdfLookup* fast = fast_lookups_[o].get();
    const OccluderShape& shape = shapes_[o];
    const OccluderField& field = *fields_.occluder[o];
    // An environment light has one direction in the occluder's frame.
    const Vec3 light_local = is_environment ? glm::normalize(occluder.inverse_linear * environment_squares_[size_t(l)].direction)
                                            : Vec3(0);
    // Which vertices' squares reach into the part's bounding cone (the
    // lookup gives exactly 1 for the others).
    if (is_environment) {
        // With the slab rule (square_lights.h): part of the factor itself, so
        // it applies with and without culling. clears_box_face's world form,
        // its division hoisted out of the loop; `&`, not `&&`, so that the
        // loop stays branch-free and vectorizes.
        const float sin_beta = square_cone_sine(environment_squares_[size_t(l)].half_edge);
        const Vec3 light = occluder.inverse_linear * environment_squares_[size_t(l)].direction / occluder.face_scale;
        for (int k = 0; k < n; ++k) {
            const float c = light_local.x * v.pole_x[k] + light_local.y * v.pole_y[k] + light_local.z * v.pole_z[k];
            s.needed[k] = s.queried[k] & int32_t(!OvdfLookup::unshadowed(c, v.cone[k], s.half[k])) &
                          int32_t(!clears_box_face(Vec3(v.side_x[k], v.side_y[k], v.side_z[k]), light, sin_beta));
        }
    } else {  // each vertex's light direction, moved into the part's frame
        const Mat3& il = occluder.inverse_linear;
        for (int k = 0; k < n; ++k) {
            const float x = il[0][0] * s.dx[k] + il[1][0] * s.dy[k] + il[2][0] * s.dz[k];
            const float y = il[0][1] * s.dx[k] + il[1][1] * s.dy[k] + il[2][1] * s.dz[k];
            const float z = il[0][2] * s.dx[k] + il[1][2] * s.dy[k] + il[2][2] * s.dz[k];
            const float c = (x * v.pole_x[k] + y * v.pole_y[k] + z * v.pole_z[k]) / std::sqrt(x * x + y * y + z * z);
            s.needed[k] = s.queried[k] & int32_t(!OvdfLookup::unshadowed(c, v.cone[k], s.half[k]));
        }
    }
    // A seam vertex leaves its neighbouring segment out (skinning.h seam_partners).
    if (s.any_partner)
        for (int k = 0; k < n; ++k) s.needed[k] &= int32_t(s.partner[k] != o);
    // The lookups visit the needed queries alone (for_each_needed).
    for (int k = 0; k < n; ++k) s.needed_bytes[k] = uint8_t(s.needed[k]);
    for (int k = n; k < kShadeBlock && k % 8 != 0; ++k) s.needed_bytes[k] = 0;
    // A split-lookup OVDF (a fast lookup exists only where prepare() takes
    // the field: renderer.cpp) goes through the batched passes.
    if (fast && shape.kind == shading::kShapeNone) return ovdf_factors(s, v, l, o, n, counts);
    for_each_needed(s.needed_bytes, n, [&](int k) {
        const int i = s.query_of[k];
        if (!(s.vis[i] > 0.0f)) return;  // black already: later occluders cannot change it
        const Vec3 dir = is_environment ? light_local
                                        : glm::normalize(occluder.inverse_linear * Vec3(s.dx[k], s.dy[k], s.dz[k]));
        if (!is_environment) {  // the slab rule for a local light's own direction
            const Vec3 light = occluder.inverse_linear * Vec3(s.dx[k], s.dy[k], s.dz[k]);
            if (clears_box_face_scaled(Vec3(v.side_x[k], v.side_y[k], v.side_z[k]), light, occluder.face_scale,
                                       square_cone_sine(s.qh[i])))
                return;
        }
        ++counts.occluder_lookups;
        if (shape.kind != shading::kShapeNone) {  // a rectangle or a box: its exact shadow (occluder_shape.h)
            // Within the field's reach only, as its lookup (and so the
            // occluder lists and culling): the part shadows nothing beyond it.
            if (!v.in_reach[k]) return;
            s.vis[i] *= shading::shape_visible_fraction(shape.kind, v.shape_point[k], v.shape_frame[k],
                                                        Vec2(s.qx[i], s.qy[i]), s.qh[i], shape.lo, shape.hi);
        } else {  // the field's own lookup (no split lookup: options, or not a coefficient-blended OVDF)
            const Vec3 point = Vec3(occluder.inverse * Vec4(s.px[k], s.py[k], s.pz[k], 1.0f));
            s.vis[i] *= field.visible_fraction(point, dir, s.qh[i]);
        }
    });
}

namespace {

struct ColorInputs {
    const float* r;
    const float* g;
    const float* b;
};

// The light's share, integral × BRDF average × visibility, of each compacted
// query i added to its vertex index[i]'s sums.
inline void add_light(int m, const int* index, const float* vis, const float* ir, const float* ig, const float* ib,
                      ColorInputs brdf, ColorOutputs sum) {
    for (int i = 0; i < m; ++i) {
        const int k = index[i];
        const float v = vis[i];
        sum.r[k] += ir[k] * brdf.r[i] * v;
        sum.g[k] += ig[k] * brdf.g[i] * v;
        sum.b[k] += ib[k] * brdf.b[i] * v;
    }
}

}  // namespace

// Point k of the block: its world position, shading frame and the view in
// that frame (towards the camera).
void CpuRenderer::set_point(BlockScratch& s, int k, const Vec3& p, const Frame& f) const {
    s.px[k] = p.x, s.py[k] = p.y, s.pz[k] = p.z;
    s.xx[k] = f.x.x, s.xy[k] = f.x.y, s.xz[k] = f.x.z;
    s.yx[k] = f.y.x, s.yy[k] = f.y.y, s.yz[k] = f.y.z;
    s.zx[k] = f.z.x, s.zy[k] = f.z.y, s.zz[k] = f.z.z;
    const Vec3 wo = f.to_local(glm::normalize(camera_ - p));
    s.vx[k] = wo.x, s.vy[k] = wo.y, s.vz[k] = wo.z;
    const Vec2 alignment = shading::view_alignment(wo);
    s.view_cos[k] = alignment.x, s.view_sin[k] = alignment.y;
}

// Light l as each of the block's n points sees it (direction, square, its
// integral) and its square's center in each point's local plane.
void CpuRenderer::set_light(BlockScratch& s, size_t l, int n) const {
    const size_t environment = environment_squares_.size();
    // The light as each vertex sees it.
    if (l < environment) {
        const SquareLight& sq = environment_squares_[l];
        for (int k = 0; k < n; ++k) put_light(s, k, sq, 1.0f);
    } else {
        for (int k = 0; k < n; ++k) put_local_light(s, k, l - environment);
    }
    const float slot = l < environment ? 1.0f : 0.0f;
    for (int k = 0; k < n; ++k) s.environment_slot[k] = slot;
    s.light_cosines = s.gains && l < environment ? s.cosines.data() + l * kShadeBlock : nullptr;
    project_lights(s, n);
}

// Slot k's light: a square (world direction, half-edge) and its integral × spot.
void CpuRenderer::put_light(BlockScratch& s, int k, const SquareLight& sq, float spot) const {
    s.dx[k] = sq.direction.x, s.dy[k] = sq.direction.y, s.dz[k] = sq.direction.z;
    s.half[k] = sq.half_edge;
    s.ir[k] = spot * sq.integral.r, s.ig[k] = spot * sq.integral.g, s.ib[k] = spot * sq.integral.b;
}

// Slot k's light: local light i as the square its sphere makes at slot k's point, with the spot's cone.
void CpuRenderer::put_local_light(BlockScratch& s, int k, size_t i) const {
    const SquareLight sq =
        sphere_light_square(Vec3(s.px[k], s.py[k], s.pz[k]), light_positions_[i], local_lights_[i].radius, light_radiance_[i]);
    put_light(s, k, sq, shading::spot_cone_factor(light_axes_[i], -sq.direction, light_cones_[i].x, light_cones_[i].y));
}

// Each point's light direction in its local frame → the equal-area plane
// point p = (x, y) / √(1 + z) of the square's center, and the local z.
void CpuRenderer::project_lights(BlockScratch& s, int n) const {
    for (int k = 0; k < n; ++k) {
        const float lx = s.dx[k] * s.xx[k] + s.dy[k] * s.xy[k] + s.dz[k] * s.xz[k];
        const float ly = s.dx[k] * s.yx[k] + s.dy[k] * s.yy[k] + s.dz[k] * s.yz[k];
        const float z = s.dx[k] * s.zx[k] + s.dy[k] * s.zy[k] + s.dz[k] * s.zz[k];
        const Vec2 p = hemisphere_to_plane(Vec3(lx, ly, z));
        s.lpx[k] = p.x, s.lpy[k] = p.y, s.lz[k] = z;
    }
}

// Every light at the block's point 0: slot l holds light l (the point, its
// frame and view copied), so that one BRDF batch serves all the lights of a
// pixel. At most kShadeBlock lights.
void CpuRenderer::set_lights_at_point(BlockScratch& s, size_t lights) const {
    const size_t environment = environment_squares_.size();
    for (size_t l = 0; l < lights; ++l) {
        const int k = int(l);
        s.px[k] = s.px[0], s.py[k] = s.py[0], s.pz[k] = s.pz[0];
        s.xx[k] = s.xx[0], s.xy[k] = s.xy[0], s.xz[k] = s.xz[0];
        s.yx[k] = s.yx[0], s.yy[k] = s.yy[0], s.yz[k] = s.yz[0];
        s.zx[k] = s.zx[0], s.zy[k] = s.zy[0], s.zz[k] = s.zz[0];
        s.vx[k] = s.vx[0], s.vy[k] = s.vy[0], s.vz[k] = s.vz[0];
        s.view_cos[k] = s.view_cos[0], s.view_sin[k] = s.view_sin[0];
        if (l < environment)
            put_light(s, k, environment_squares_[l], 1.0f);
        else
            put_local_light(s, k, l - environment);
        s.environment_slot[k] = l < environment ? 1.0f : 0.0f;
        s.partner[k] = -1;  // a pixel takes every occluder's shadow, on either backend
    }
    s.any_partner = false;
    s.light_cosines = nullptr;  // each slot's c from its own square (brdf_queries)
    project_lights(s, int(lights));
}

// Light l's queries among the block's n points (after set_light), compacted
// into s.index, s.qx/qy/qh (the square in the point's frame) and s.tx/ty
// (in the table's frame), with their BRDF averages in s.br/bg/bb (and the
// specular table's in s.spr/spg/spb). Returns their count m.
int CpuRenderer::brdf_queries(BlockScratch& s, const BrdfTable& table, const BrdfTable* specular, int n,
                           const float* view_floor) const {
    const bool isotropic = table.isotropic();
    // Compaction: the view must be above the horizon (ρ = 0 otherwise, as
    // the truth; above view_floor: queried with ρ = 0) and the square must reach
    // the upper hemisphere.
    int m = 0;
    bool away = false;  // a query whose view is below the horizon
    for (int k = 0; k < n; ++k) s.queried[k] = 0;
    for (int k = 0; k < n; ++k) {
        if (!(s.half[k] > 0.0f) || !square_reaches_hemisphere(s.lz[k], s.half[k])) continue;
        const bool faces_away = !(s.vz[k] > 0.0f);
        if (faces_away && !(view_floor && s.vz[k] > view_floor[k])) continue;
        away = away || faces_away;
        s.skip[m] = faces_away;  // its averages are set to 0 below
        s.queried[k] = 1;
        s.query_of[k] = m;
        s.index[m] = k;
        s.qx[m] = s.lpx[k], s.qy[m] = s.lpy[k], s.qh[m] = s.half[k];
        if (isotropic) {  // view-aligned frame: rotate about the normal (to_view_aligned)
            const Vec2 t = shading::to_view_aligned(Vec2(s.lpx[k], s.lpy[k]), Vec2(s.view_cos[k], s.view_sin[k]));
            s.tx[m] = t.x, s.ty[m] = t.y;
        } else {
            s.tx[m] = s.lpx[k], s.ty[m] = s.lpy[k];
            s.qvx[m] = faces_away ? 0.0f : s.vx[k], s.qvy[m] = faces_away ? 0.0f : s.vy[k];
        }
        s.qvz[m] = faces_away ? 1.0f : s.vz[k];  // any view the tables take: the averages are 0
        ++m;
    }
    if (m == 0) return 0;

    SquareQueries queries;
    queries.center_x = s.tx, queries.center_y = s.ty;
    queries.half_edge = s.qh;
    queries.view_x = isotropic ? nullptr : s.qvx;
    queries.view_y = isotropic ? nullptr : s.qvy;
    queries.view_z = s.qvz;
    queries.count = size_t(m);
    if (s.pbr) {
        pbr_averages(s, queries, m, specular != nullptr);
    } else {
        table.square_average_batch(queries, ColorOutputs{s.br, s.bg, s.bb});
        if (specular) specular->square_average_batch(queries, ColorOutputs{s.spr, s.spg, s.spb});
    }
    if (s.gains)  // the exact diffuse light: g·c_l on the (diffuse) table's average
        for (int i = 0; i < m; ++i) {
            const int k = s.index[i];
            const float c = s.light_cosines ? s.light_cosines[k]
                                            : s.environment_slot[k] *
                                                  shading::square_average_cosine(Vec2(s.lpx[k], s.lpy[k]), s.half[k]);
            s.br[i] += s.gain_r[k] * c, s.bg[i] += s.gain_g[k] * c, s.bb[i] += s.gain_b[k] * c;
        }
    if (away)
        for (int i = 0; i < m; ++i)
            if (s.skip[i]) {
                s.br[i] = s.bg[i] = s.bb[i] = 0.0f;
                if (specular) s.spr[i] = s.spg[i] = s.spb[i] = 0.0f;
            }
    return m;
}

// The other parts' shadows on the block's m queries of light l: each
// occluder's factor (receiver point and light direction in the occluder's
// frame) multiplied into s.vis. The occluders are the part's list for the
// light (culling.h), or a given list: then `growth`, the lists' footprint
// growth per entry, may be null, and the part-level light test is skipped
// (it only saves time).
void CpuRenderer::shadow_by_occluders(BlockScratch& s, const BoundingSphere& block_sphere, int part_index, size_t l,
                                   int n, int m, RenderStats& counts) const {
    const size_t slot = size_t(part_index) * (environment_squares_.size() + light_positions_.size()) + l;
    const size_t first = offsets_[slot];
    shadow_by_occluders(s, block_sphere, std::span<const int>(occluders_).subspan(first, offsets_[slot + 1] - first),
                        occluder_growth_.data() + first, l, n, m, counts);
}

void CpuRenderer::shadow_by_occluders(BlockScratch& s, const BoundingSphere& block_sphere, std::span<const int> occluders,
                                   const float* growth, size_t l, int n, int m, RenderStats& counts) const {
    const bool vertex_culling = options_.occluder_culling;
    for (size_t e = 0; e < occluders.size(); ++e) {
        const int o = occluders[e];
        if (!block_may_be_shadowed(s, block_sphere, o, growth ? growth[e] : -1.0f, l)) {
            ++counts.block_occluders_culled;
            continue;
        }
        BlockScratch::BlockOccluder& b = s.occluders[size_t(o)];
        OccluderVertexScratch& v = b.vertices ? *b.vertices : prepare_occluder_vertices(s, o, n, vertex_culling);
        occluder_factors(s, v, int(l), o, n, m, counts);
    }
}

// Whether occluder o may shadow some point of the block from light l (false
// only when certain). The block-level tests: beyond the field's reach; for
// an environment light, the part's bounding cone seen from the block, then
// (as the per-part test; growth < 0: skipped) the light's cone against the
// part's sphere, the block grown by `growth`.
bool CpuRenderer::block_may_be_shadowed(BlockScratch& s, const BoundingSphere& block_sphere, int o, float growth,
                                     size_t l) const {
    const bool vertex_culling = options_.occluder_culling;
    BlockScratch::BlockOccluder& b = s.occluders[size_t(o)];
    if (b.stamp != s.stamp) prepare_occluder(s, block_sphere, o, vertex_culling);
    if (b.outside) return false;
    if (!vertex_culling || l >= environment_squares_.size()) return true;
    const PartPose& occluder = poses_[o];
    const SquareLight& sq = environment_squares_[l];
    if (occluder.uniform_scale && block_unshadowed(b.pole, b.spread, b.cone, sq.direction, sq.half_edge)) return false;
    const BoundingSphere grown{block_sphere.center, block_sphere.radius + std::max(growth, 0.0f)};
    return growth < 0.0f ||
           may_shadow_direction(grown, occluder.world_bounds, sq.direction, square_cone_half_angle(sq.half_edge));
}

// The block's vertices into the scratch: world position, shading frame (as
// PosedScene::vertex) and local view, and a fresh stamp for its occluders.
void CpuRenderer::load_block_points(BlockScratch& s, const Block& block) const {
    const TriangleMesh& mesh = scene_.parts[size_t(block.part)].mesh;
    const PartPose& pose = poses_[size_t(block.part)];
    const int* const order = block_order_[size_t(block.part)].data() + block.begin;
    const bool has_tangents = !mesh.tangents.empty();
    // A skinned part's vertices as posed this frame (src/core/skinning.h).
    const PosedVertices* skinned = frame_.skinned(size_t(block.part));
    const std::vector<Vec3>& positions = skinned ? skinned->positions : mesh.positions;
    const std::vector<Vec3>& normals = skinned ? skinned->normals : mesh.normals;
    const std::vector<Vec4>& tangents = skinned ? skinned->tangents : mesh.tangents;
    const std::vector<int>& partners = seam_partners_[size_t(block.part)];
    s.any_partner = false;
    if (s.occluders.size() != scene_.parts.size()) s.occluders.assign(scene_.parts.size(), {});  // first block only
    ++s.stamp;  // every part's BlockOccluder is stale
    s.pool_used = 0;
    for (int k = 0; k < block.end - block.begin; ++k) {
        const int v = order[k];
        s.vertex[k] = v;
        s.partner[k] = partners.empty() ? -1 : partners[size_t(v)];
        s.any_partner = s.any_partner || s.partner[k] >= 0;
        const Vec3 normal = glm::normalize(pose.normal * normals[v]);
        const Vec3 tangent = has_tangents ? pose.linear * Vec3(tangents[v]) : Vec3(0);
        set_point(s, k, Vec3(pose.transform * Vec4(positions[v], 1.0f)), Frame::from_normal_tangent(normal, tangent));
    }
}

// The bounding sphere of the block's n points for block-level culling: the
// shading core's (src/shading/culling.h point_box), as the GPU's workgroups
// compute it (shaders/shade_blocks.comp.glsl).
BoundingSphere CpuRenderer::block_bounding_sphere(const BlockScratch& s, int n) {
    shading::PointBox box = shading::point_box(Vec3(s.px[0], s.py[0], s.pz[0]));
    for (int k = 1; k < n; ++k) box = shading::point_box_add(box, Vec3(s.px[k], s.py[k], s.pz[k]));
    BoundingSphere sphere;
    sphere.center = shading::point_box_center(box);
    float r2 = 0;
    for (int k = 0; k < n; ++k) r2 = shading::farther_squared(r2, sphere.center, Vec3(s.px[k], s.py[k], s.pz[k]));
    sphere.radius = shading::bounding_radius(r2);
    return sphere;
}

std::vector<uint32_t> CpuRenderer::block_candidate_lights(size_t b) const {
    RSL_CHECK(b < blocks_.size());
    const Block& block = blocks_[b];
    auto scratch = std::make_unique<BlockScratch>();
    BlockScratch& s = *scratch;
    load_block_points(s, block);
    const BoundingSphere sphere =
        options_.occluder_culling ? block_bounding_sphere(s, block.end - block.begin) : BoundingSphere{};
    const OccluderLists& lists = frame_.occluder_lists();
    const size_t first = lists.candidate_offsets[size_t(block.part)];
    const size_t last = lists.candidate_offsets[size_t(block.part) + 1];
    const size_t words = lists.light_words;
    std::vector<uint32_t> bits((last - first) * words, 0u);
    for (size_t c = first; c < last; ++c)
        for (size_t l = 0; l < words * 32; ++l)
            if ((lists.candidate_lights[c * words + l / 32] >> (l % 32)) & 1u &&
                block_may_be_shadowed(s, sphere, lists.candidate_occluders[c], lists.candidate_growths[c], l))
                bits[(c - first) * words + l / 32] |= 1u << (l % 32);
    return bits;
}

// The block's vertices' terms for the image (pixel_shading.cpp), reset
// before the lights add to them; `terms` null for a part shaded per vertex.
CpuRenderer::BlockPixelTerms CpuRenderer::start_block_pixel_terms(BlockScratch& s, int part, bool textured, int n,
                                                                  size_t lights) {
    BlockPixelTerms kept;
    PixelTerms& terms = pixel_terms_[size_t(part)];
    // A textured part keeps both layers' terms (CpuRenderer::shade sizes them).
    if (terms.occlusion.empty() || (textured && terms.unshadowed_specular.empty())) return kept;
    kept.terms = &terms;
    kept.unshadowed = !terms.unshadowed.empty();
    kept.specular = kept.unshadowed && textured;
    kept.self = !terms.self_visibility.empty();
    if (kept.self) {
        for (int k = 0; k < n; ++k) s.view_floor[k] = rim_view_floor_[size_t(part)][size_t(s.vertex[k])];
        kept.rim_floor = s.view_floor;
    }
    for (int k = 0; k < n; ++k) {
        const size_t first = size_t(s.vertex[k]) * lights, last = first + lights;
        std::fill(terms.occlusion.begin() + first, terms.occlusion.begin() + last, 1.0f);
        if (kept.unshadowed) std::fill(terms.unshadowed.begin() + first, terms.unshadowed.begin() + last, Color(0));
        if (kept.specular)
            std::fill(terms.unshadowed_specular.begin() + first, terms.unshadowed_specular.begin() + last, Color(0));
        if (kept.self) std::fill(terms.self_visibility.begin() + first, terms.self_visibility.begin() + last, 0.0f);
    }
    return kept;
}

// The part's own visibility of the m queried squares into s.vis: the SVDF,
// or exact rays (RenderOptions::exact_visibility); 0 where the square adds
// nothing, unless the pixels keep the SVDF (`keep_self`).
void CpuRenderer::block_self_visibility(BlockScratch& s, int part, int light, const BrdfTable* specular, int m,
                                        bool keep_self, RenderStats& counts) const {
    const Svdf* svdf = options_.self_visibility ? fields_.self[part].get() : nullptr;
    // A square whose BRDF average is 0 (clipped away below the horizon)
    // adds nothing whatever its visibility: no visibility lookups (nor rays) for it.
    auto adds_nothing = [&](int i) {
        return s.br[i] == 0.0f && s.bg[i] == 0.0f && s.bb[i] == 0.0f &&
               (!specular || (s.spr[i] == 0.0f && s.spg[i] == 0.0f && s.spb[i] == 0.0f));
    };
    const ExactVisibility* exact = options_.exact_visibility.get();
    const ExactVisibilityMode exact_mode = exact ? exact->mode() : ExactVisibilityMode::All;
    const bool exact_others = exact_mode == ExactVisibilityMode::Others || exact_mode == ExactVisibilityMode::OthersProduct;
    if (exact && !exact_others) {
        for (int i = 0; i < m; ++i) s.skip[i] = adds_nothing(i);
        exact->visible_fraction_batch(part, 0, light, s.query_vertex, s.qx, s.qy, s.qh, s.skip, m, s.vis, &counts.shadow_rays);
    } else if (svdf) {
        svdf->visible_fraction_batch(0, s.query_vertex, s.qx, s.qy, s.qh, m, s.vis);
    } else {
        for (int i = 0; i < m; ++i) s.vis[i] = 1.0f;
    }
    // Highlights per pixel keep the SVDF of every square that reaches the
    // vertex's hemisphere: a pixel near the vertex may see the light.
    if (!keep_self)
        for (int i = 0; i < m; ++i)
            if (adds_nothing(i)) s.vis[i] = 0.0f;
    if (exact && exact_others) {
        for (int i = 0; i < m; ++i) s.skip[i] = !(s.vis[i] > 0.0f);
        exact->visible_fraction_batch(part, 0, light, s.query_vertex, s.qx, s.qy, s.qh, s.skip, m, s.exact,
                                      &counts.shadow_rays);
        for (int i = 0; i < m; ++i) s.vis[i] *= s.exact[i];
    }
}

// Light l's terms of the m queried vertices for the image: the other parts'
// shadows' factor (s.vis over the visibility before them, `unshadowed_vis`),
// and the light's share or the SVDF's without it.
void CpuRenderer::keep_block_pixel_terms(const BlockScratch& s, const BlockPixelTerms& kept, size_t lights, size_t l,
                                         int m) {
    PixelTerms& terms = *kept.terms;
    for (int i = 0; i < m; ++i) {
        const int k = s.index[i];
        const size_t at = size_t(s.vertex[k]) * lights + l;
        const float before = s.unshadowed_vis[i];
        terms.occlusion[at] = before > 0.0f ? s.vis[i] / before : 1.0f;
        if (kept.unshadowed)
            terms.unshadowed[at] = before * Color(s.ir[k] * s.br[i], s.ig[k] * s.bg[i], s.ib[k] * s.bb[i]);
        if (kept.specular)
            terms.unshadowed_specular[at] = before * Color(s.ir[k] * s.spr[i], s.ig[k] * s.spg[i], s.ib[k] * s.spb[i]);
        if (kept.self) terms.self_visibility[at] = before;
    }
}

// Σ_l I_l · B_l · V_l · F_l over the block's vertices (docs/design/RENDERER.md):
// per light, the BRDF averages, the part's own visibility, the other parts'
// shadows, then the sum.
void CpuRenderer::shade_block(const Block& block, VertexColors& out, RenderStats& counts) {
    thread_local BlockScratch scratch;
    BlockScratch& s = scratch;
    const int part_index = block.part;
    const BrdfTable& table = *part_tables_[part_index];
    // A textured part's second lobe: the same squares and visibility, a second table.
    const BrdfTable* specular = part_specular_tables_[part_index];
    RSL_CHECK(!specular || specular->isotropic() == table.isotropic());
    const int n = block.end - block.begin;
    load_block_points(s, block);
    load_block_pbr(s, part_index, n);
    diffuse_light_gains(s, part_index, n);
    const BoundingSphere block_sphere = options_.occluder_culling ? block_bounding_sphere(s, n) : BoundingSphere{};
    for (int k = 0; k < n; ++k) {
        s.r[k] = s.g[k] = s.b[k] = 0.0f;
        s.sr[k] = s.sg[k] = s.sb[k] = 0.0f;
    }
    const size_t environment = environment_squares_.size();
    const size_t lights = environment + light_positions_.size();
    const BlockPixelTerms pixel = start_block_pixel_terms(s, part_index, specular != nullptr, n, lights);
    const ExactVisibility* exact = options_.exact_visibility.get();
    const bool field_occluders = !exact || exact->mode() == ExactVisibilityMode::Self;

    for (size_t l = 0; l < lights; ++l) {
        if (l < environment ? !options_.environment : !options_.local_lights) continue;
        set_light(s, l, n);
        const int m = brdf_queries(s, table, specular, n, pixel.rim_floor);
        if (m == 0) continue;
        counts.lookups += size_t(m);
        for (int i = 0; i < m; ++i) s.query_vertex[i] = s.vertex[s.index[i]];
        if (pixel.rim_floor)  // the rim's queries kept for the pixels are not the frame's lookups
            for (int i = 0; i < m; ++i) counts.lookups -= s.skip[i] ? 1 : 0;
        block_self_visibility(s, part_index, int(l), specular, m, pixel.self, counts);
        if (pixel.terms)
            for (int i = 0; i < m; ++i) s.unshadowed_vis[i] = s.vis[i];
        if (field_occluders) shadow_by_occluders(s, block_sphere, part_index, l, n, m, counts);
        if (pixel.terms) keep_block_pixel_terms(s, pixel, lights, l, m);
        add_light(m, s.index, s.vis, s.ir, s.ig, s.ib, ColorInputs{s.br, s.bg, s.bb}, ColorOutputs{s.r, s.g, s.b});
        if (specular)
            add_light(m, s.index, s.vis, s.ir, s.ig, s.ib, ColorInputs{s.spr, s.spg, s.spb},
                      ColorOutputs{s.sr, s.sg, s.sb});
    }

    std::vector<Color>& colors = out.parts[part_index];
    for (int k = 0; k < n; ++k) colors[size_t(s.vertex[k])] = Color(s.r[k], s.g[k], s.b[k]);
    if (specular) {
        std::vector<Color>& layer = out.specular[part_index];
        for (int k = 0; k < n; ++k) layer[size_t(s.vertex[k])] = Color(s.sr[k], s.sg[k], s.sb[k]);
    }
    counts.vertices += size_t(n);
}

}  // namespace rsl
