// The CPU renderer's OVDF lookups of one (light, occluder) over a block's
// needed queries, in passes over structure-of-arrays lists rather than one
// query at a time: the queries still lit are listed (with a local light's
// own direction and slab rule), the vertices not yet located are located
// in one batch (Ovdf::locate_near), the small-occluder rule — most lookups
// in a scene of many parts — is decided and evaluated for every listed
// query in one vectorized loop, and only the lookups that need the tables
// take the scalar path (OvdfLookup). The values are OvdfLookup::
// visible_fraction's (tests/render/ovdf_lookup_test.cpp pins the rule on
// the batch's values to the field's own lookup).
#include "src/render/block_scratch.h"
#include "src/render/ovdf_lookup.h"
#include "src/render/cpu_renderer.h"
#include "src/shading/ovdf_small_occluder.h"

namespace rsl {

namespace {

// The listed vertices' OVDF points located in one batch (Ovdf::locate_near)
// and kept in the vertex scratch's near_ arrays; the few within the
// bounding sphere (the inside test) or beyond the outer shell get their
// full point one at a time.
void locate_near_points(NearLocations& b, OccluderVertexScratch& v, const OvdfLookup& fast, int count) {
    OvdfNearPoints batch;
    batch.count = count;
    batch.x = b.x, batch.y = b.y, batch.z = b.z;
    batch.cone = b.cone, batch.occluded_area = b.occluded_area;
    batch.pole_x = b.pole_x, batch.pole_y = b.pole_y, batch.pole_z = b.pole_z;
    batch.near = b.near;
    fast.field().locate_near(batch);
    for (int j = 0; j < count; ++j) {
        const int k = b.vertex[j];
        if (!b.near[j]) {
            fast.locate(Vec3(b.x[j], b.y[j], b.z[j]), v.points[k]);
            v.located[k] = OccluderVertexScratch::kPoint;
            continue;
        }
        v.located[k] = OccluderVertexScratch::kNear;
        v.near_cone[k] = b.cone[j];
        v.near_area[k] = b.occluded_area[j];
        v.near_pole_x[k] = b.pole_x[j], v.near_pole_y[k] = b.pole_y[j], v.near_pole_z[k] = b.pole_z[j];
    }
}

}  // namespace

void CpuRenderer::ovdf_factors(BlockScratch& s, OccluderVertexScratch& v, int l, int o, int n,
                            RenderStats& counts) const {
    const PartPose& occluder = poses_[o];
    const OvdfLookup& fast = *fast_lookups_[o];
    const bool is_environment = size_t(l) < environment_squares_.size();
    const Vec3 light_local = is_environment
                                 ? glm::normalize(occluder.inverse_linear * environment_squares_[size_t(l)].direction)
                                 : Vec3(0);
    BlockScratch::OvdfQueries& b = s.ovdf;
    NearLocations& unlocated = s.near;
    // The needed queries whose visibility is not black already (later
    // occluders cannot change it), and among them the vertices to locate.
    int count = 0, to_locate = 0;
    for_each_needed(s.needed_bytes, n, [&](int k) {
        const int i = s.query_of[k];
        if (!(s.vis[i] > 0.0f)) return;
        Vec3 dir = light_local;
        if (!is_environment) {  // the light's direction at this vertex, and the slab rule for it
            const Vec3 light = occluder.inverse_linear * Vec3(s.dx[k], s.dy[k], s.dz[k]);
            if (clears_box_face_scaled(Vec3(v.side_x[k], v.side_y[k], v.side_z[k]), light, occluder.face_scale,
                                       square_cone_sine(s.qh[i])))
                return;
            dir = glm::normalize(light);
        }
        b.vertex[count] = k, b.query[count] = i, b.half_edge[count] = s.qh[i];
        b.dir_x[count] = dir.x, b.dir_y[count] = dir.y, b.dir_z[count] = dir.z;
        ++count;
        if (v.located[k] == OccluderVertexScratch::kUnlocated) {
            unlocated.x[to_locate] = v.local_x[k], unlocated.y[to_locate] = v.local_y[k];
            unlocated.z[to_locate] = v.local_z[k];
            unlocated.vertex[to_locate++] = k;
        }
    });
    counts.occluder_lookups += size_t(count);
    if (count == 0) return;
    if (to_locate > 0) locate_near_points(unlocated, v, fast, to_locate);

    // The small-occluder rule (OvdfLookup::visible_fraction's w = 1 case) for
    // every query whose vertex is Near: whether it applies, and its value.
    // Branch-free; a vertex that is not Near reads stand-ins (dropped).
    RSL_VECTORIZE_NO_ALIAS
    for (int j = 0; j < count; ++j) {
        const int k = b.vertex[j];
        const bool near = v.located[k] == OccluderVertexScratch::kNear;
        const float cone = near ? v.near_cone[k] : 0.0f;
        const float area = near ? v.near_area[k] : 0.0f;
        const float pole_x = near ? v.near_pole_x[k] : 0.0f;
        const float pole_y = near ? v.near_pole_y[k] : 0.0f;
        const float pole_z = near ? v.near_pole_z[k] : 1.0f;
        const float h = b.half_edge[j];
        b.small[j] = near && shading::ovdf_small_occluder_weight(cone, h, area) >= 1.0f;
        const float cos_to_pole = b.dir_x[j] * pole_x + b.dir_y[j] * pole_y + b.dir_z[j] * pole_z;
        b.fraction[j] = shading::ovdf_small_occluder_fraction(shading::ovdf_pole_radial(cos_to_pole), area, cone, h);
    }
    // The products (each query once per occluder: none reordered), and the
    // lookups that need the tables one at a time.
    for (int j = 0; j < count; ++j) {
        const int i = b.query[j];
        if (b.small[j]) {
            s.vis[i] *= b.fraction[j];
            continue;
        }
        const int k = b.vertex[j];
        const float h = b.half_edge[j];
        const Vec3 point(v.local_x[k], v.local_y[k], v.local_z[k]);
        OvdfPoint& q = v.points[k];
        if (v.located[k] == OccluderVertexScratch::kNear) {  // a light narrower than the part's cone: the full location
            fast.locate(point, q);
            v.located[k] = OccluderVertexScratch::kPoint;
        }
        // The terms only for a light narrower than the part's cone (small occluders need none).
        if (OvdfLookup::needs_terms(q, h)) v.terms_used += fast.complete(q, v.terms + v.terms_used);
        s.vis[i] *= fast.visible_fraction(q, point, Vec3(b.dir_x[j], b.dir_y[j], b.dir_z[j]), h);
    }
}

}  // namespace rsl
