// Ovdf::locate_near: the near half of a receiver's location (cone, blended
// occluded area, pole) for many receivers at once. The CPU renderer locates
// one point per (vertex, occluder) that a light needs, millions a frame in a
// dense scene, and the small-occluder rule needs only this half; one point
// at a time it was over a quarter of such a frame's profile (calls, a Frame
// built and dropped, a branch per shell, a call to the library's log). The same
// formulas in the same order as Ovdf::locate and blend_samples, so the
// results are theirs (tests/fields/ovdf_near_test.cpp); the loop is
// branch-free for the vectorizer.
#include <cmath>

#include "src/fields/ovdf.h"
#include "src/shading/interpolation.h"
#include "src/shading/ovdf_tables.h"

namespace rsl {

void Ovdf::locate_near(const OvdfNearPoints& points) const {
    const int count = points.count;
    const float outer = shell_radii_.back();
    const float* const px = points.x;
    const float* const py = points.y;
    const float* const pz = points.z;
    const int n = params.cube_resolution, shells = params.shells;
    const float* const area = occluded_area.empty() ? nullptr : occluded_area.data();
    const float* const face_s = &face_s_[0].x;
    const float* const face_t = &face_t_[0].x;
    const Vec3* const normals = face_normal_.data();
    const Vec3 c = center;
    const float r = radius;
    const int spacing = int(params.spacing);
    const float inner = params.inner_radius, outer_ratio = params.outer_radius;
    RSL_VECTORIZE_NO_ALIAS
    for (int j = 0; j < count; ++j) {
        const float d0 = glm::length(Vec3(px[j], py[j], pz[j]) - c);
        // Between the bounding sphere and the outer shell (and off the
        // centre, for a degenerate part of radius 0); the other lanes go on
        // with a harmless stand-in (no NaN reaches an index).
        const bool near = d0 < outer && !(d0 < r) && d0 > 0.0f;
        const float d = near ? d0 : 1.0f;
        const float ox = near ? px[j] - c.x : 0.0f, oy = near ? py[j] - c.y : 0.0f, oz = near ? pz[j] - c.z : 1.0f;
        const float inverse = 1.0f / d;
        const Vec3 dir(ox * inverse, oy * inverse, oz * inverse);
        // ovdf_zoom's cone; the shell pair, cube face and sample taps as locate().
        points.cone[j] = d <= r ? kOvdfNoCone : shading::ovdf_cone_radius(d, r);
        const shading::LerpPair pair =
            shading::ovdf_shell_pair(shading::ovdf_shell_coordinate(spacing, shells, inner, outer_ratio, d / r), shells);
        const shading::CubeFace face = shading::cube_face(dir, normals);
        const Vec3 s(face_s[3 * face.face], face_s[3 * face.face + 1], face_s[3 * face.face + 2]);
        const Vec3 t(face_t[3 * face.face], face_t[3 * face.face + 1], face_t[3 * face.face + 2]);
        const shading::SampleTaps taps = shading::ovdf_sample_taps(dir, face.cosine, s, t, n);
        // blend_samples: both shells (a shell of weight 0 adds 0).
        if (area) {
            float blended = 0.0f;
            for (int k = 0; k < 2; ++k) {
                const float ws = k == 0 ? 1.0f - pair.upper_weight : pair.upper_weight;
                float value = 0.0f;
                for (int q = 0; q < 4; ++q)
                    value += taps.weight[q] * area[shading::ovdf_sample_index(pair.lower + k, face.face, taps.i[q], taps.j[q], n)];
                blended += ws * value;
            }
            points.occluded_area[j] = blended;
        } else {
            points.occluded_area[j] = shading::kOvdfNoAreaBound;
        }
        // As locate()'s pole frame: z = normalize(−dir).
        const Vec3 pole = glm::normalize(-dir);
        points.pole_x[j] = pole.x, points.pole_y[j] = pole.y, points.pole_z[j] = pole.z;
        points.near[j] = near;
    }
}

}  // namespace rsl
