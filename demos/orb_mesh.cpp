#include "demos/orb_mesh.h"

#include <fmt/format.h>

#include "assets/generate/primitives.h"
#include "src/core/atomic_file.h"

namespace rsl::demos {

TriangleMesh make_orb_mesh() {
    constexpr float kSphereRadius = 0.2f, kRingMajor = 0.27f, kRingMinor = 0.03f, kSpacing = 0.032f;
    constexpr float kCenterY = kSphereRadius + 0.005f;  // a hair above the floor: no coplanar contact
    TriangleMesh orb = assets::sphere(kSphereRadius, kSpacing);
    assets::transform_mesh(orb, assets::translate_rotate(Vec3(0, kCenterY, 0)));
    // Thin tube: finer spacing around it, so its cross-section stays round.
    TriangleMesh ring = assets::torus(kRingMajor, kRingMinor, 0.75f * kSpacing);
    assets::transform_mesh(ring, assets::translate_rotate(Vec3(0, kCenterY, 0), Vec3(1, 0, 0.3f), 0.5f));
    assets::append_mesh(orb, ring);
    orb.name = "orb";
    return orb;
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const std::string& comment) {
    std::string text = fmt::format("# {}\n# {} vertices, {} triangles\n", comment, mesh.vertex_count(),
                                   mesh.triangle_count());
    for (const Vec3& p : mesh.positions) text += fmt::format("v {:.5g} {:.5g} {:.5g}\n", p.x, p.y, p.z);
    for (const Vec3& n : mesh.normals) text += fmt::format("vn {:.5g} {:.5g} {:.5g}\n", n.x, n.y, n.z);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t a = mesh.indices[3 * t] + 1, b = mesh.indices[3 * t + 1] + 1, c = mesh.indices[3 * t + 2] + 1;
        text += fmt::format("f {}//{} {}//{} {}//{}\n", a, a, b, b, c, c);
    }
    write_file_atomically(path, text);
}

}  // namespace rsl::demos
