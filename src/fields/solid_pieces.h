#pragma once
// Whether a point lies inside a part, for the OVDF bake (src/fields/ovdf.cpp):
// a shell sample inside the part traces its table from the surface outside
// it instead, and stores a negative surface distance.
//
// A point is inside when nearly all (12) of the 14 probe rays from it meet
// the part from behind, leaving through a face that turns outwards; the
// others may escape through a small hole (field format 8 on: fields baked
// under the earlier rule, which had every probe hit, are baked again). That
// alone fails where a part is several closed pieces that overlap — a
// robot's waist cone sunk into its pelvis box, a chair's legs into its
// seat, a glTF node whose primitives were joined: a ray from inside one
// piece may first meet another piece's faces from outside. So the test
// also runs on each closed piece alone (triangles joined by shared edges,
// their vertices welded by position so that UV and normal seams do not
// split a surface, while pieces touching at a vertex stay two), and a point
// inside one of them is inside the part. A piece with a hole (an edge of one
// triangle, or three: a cup, a riser glued onto a slab) is left to the
// whole-mesh test, as is everything of an open mesh (a ground plane, which
// lets probes escape). Triangles that turn inwards (a room's walls seen from
// inside, negative signed volume) enclose nothing. Limits: the whole-mesh
// test takes the bottom of a deep cup, whose walls meet every probe from
// behind, for inside (as it always did), and a hollow ball's cavity counts
// as solid, since its outer surface alone encloses it.
#include <memory>
#include <optional>
#include <vector>

#include "src/core/mesh.h"
#include "src/rays/ray_scene.h"

namespace rsl {

class SolidPieces {
public:
    // With `only_around`, only the pieces whose box holds that point are kept
    // (their ray scenes are the cost): inside() is then right for it alone.
    explicit SolidPieces(const TriangleMesh& mesh, const std::optional<Vec3>& only_around = std::nullopt);
    ~SolidPieces();
    SolidPieces(const SolidPieces&) = delete;
    SolidPieces& operator=(const SolidPieces&) = delete;

    // The closed pieces turned outwards.
    int piece_count() const { return int(pieces_.size()); }
    // Inside the part, and the nearest hit of the probe rays on the whole
    // mesh (an upper bound on the distance to the surface). Thread-safe.
    struct Probe {
        bool inside = false;
        float nearest = 1e30f;
    };
    Probe probe(const Vec3& point) const;
    bool inside(const Vec3& point) const { return probe(point).inside; }
    // The whole mesh, for rays (the OVDF bake traces its tables in it).
    const RayScene& whole() const { return whole_; }

    // The probe directions: the axes and cube diagonals turned a little, so
    // that they do not run along the faces and through the edges of
    // axis-aligned geometry, where a ray can slip between two triangles.
    static constexpr int kProbes = 14;
    static const Vec3* probe_directions();

private:
    struct Piece {
        Vec3 lo, hi;           // bounding box: no point outside it is inside the piece
        RayScene scene;
    };
    RayScene whole_;
    std::vector<std::unique_ptr<Piece>> pieces_;
};

}  // namespace rsl
