#include "src/fields/ovdf_spans.h"

#include <tbb/parallel_for.h>

#include "src/shading/ovdf_tables.h"
#include "src/shading/ovdf_inside.h"

namespace rsl {

Vec3 ovdf_span_direction(int face, int i, int j, int n) {
    const int axis = face / 2;
    Vec3 dir(0.0f);
    dir[axis] = face % 2 == 0 ? 1.0f : -1.0f;
    dir[(axis + 1) % 3] = (float(i) + 0.5f) / float(n) * 2.0f - 1.0f;
    dir[(axis + 2) % 3] = (float(j) + 0.5f) / float(n) * 2.0f - 1.0f;
    return glm::normalize(dir);
}

std::vector<float> bake_radial_spans(const SolidPieces& pieces, const Vec3& center, float radius, int n) {
    const int lines = shading::kCubeFaces * n * n;
    std::vector<float> spans(size_t(2 * lines), 0.0f);
    const bool center_inside = pieces.inside(center);
    const RayScene& scene = pieces.whole();
    const float start = 1.01f * radius;  // just outside the bounding sphere
    const float step = 1e-5f * radius;   // past a hit, so that it is not met again
    constexpr int kMostHits = 64;
    tbb::parallel_for(0, lines, [&](int line) {
        const int face = line / (n * n), j = (line / n) % n, i = line % n;
        const Vec3 inward = -ovdf_span_direction(face, i, j, n);
        const Vec3 origin = center - start * inward;
        float enter = 0.0f, exit = 0.0f, t = 0.0f;
        int depth = 0;
        bool entered = false, left = false;
        for (int hit_count = 0; hit_count < kMostHits; ++hit_count) {
            const RayHit hit = scene.intersect(origin, inward, t, start);
            if (!hit.hit) break;
            t = hit.t + step;
            if (glm::dot(hit.geometric_normal, inward) < 0.0f) {  // a face turned towards the line: in
                if (!entered) enter = start - hit.t;
                entered = true;
                ++depth;
            } else if (depth > 0 && --depth == 0) {
                exit = start - hit.t;
                left = true;
                break;
            }
        }
        if (entered && !left) exit = center_inside ? 0.0f : enter;
        spans[size_t(2 * line)] = enter;
        spans[size_t(2 * line + 1)] = exit;
    });
    return spans;
}

}  // namespace rsl
