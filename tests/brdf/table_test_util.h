#pragma once
// Brute-force references for the BRDF table tests.
#include "src/brdf/brdf.h"
#include "src/core/hemisphere.h"

namespace rsl::test {

// Average of ρ·cosθ_i over the plane square [c − h, c + h]² by m×m midpoint
// sampling (directions through the equal-area map; outside the unit disk
// counts as 0), divided by the full square's area: exactly what the table
// approximates, without any table.
inline DVec3 brute_square_average(const Brdf& brdf, const Vec2& c, float h, const Vec3& wo, int m) {
    DVec3 sum(0.0);
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            const Vec2 p = c + h * Vec2(-1.0f + (2.0f * i + 1.0f) / m, -1.0f + (2.0f * j + 1.0f) / m);
            if (glm::dot(p, p) >= 1.0f) continue;
            const Vec3 wi = plane_to_hemisphere(p);
            sum += DVec3(brdf.eval(wi, wo)) * double(wi.z);
        }
    return sum / double(m * m);
}

}  // namespace rsl::test
