#include "tools/assets/orb.h"

#include "tools/assets/primitives.h"

namespace rsl::assets {

TriangleMesh make_orb() {
    constexpr float kSphereRadius = 0.2f, kRingMajor = 0.27f, kRingMinor = 0.03f, kSpacing = 0.032f;
    constexpr float kCenterY = kSphereRadius + 0.005f;  // a hair above the floor: no coplanar contact
    TriangleMesh orb = sphere(kSphereRadius, kSpacing);
    transform_mesh(orb, translate_rotate(Vec3(0, kCenterY, 0)));
    // Thin tube: finer spacing around it, so its cross-section stays round.
    TriangleMesh ring = torus(kRingMajor, kRingMinor, 0.75f * kSpacing);
    transform_mesh(ring, translate_rotate(Vec3(0, kCenterY, 0), Vec3(1, 0, 0.3f), 0.5f));
    append_mesh(orb, ring);
    orb.name = "orb";
    return orb;
}

}  // namespace rsl::assets
