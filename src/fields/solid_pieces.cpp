#include "src/fields/solid_pieces.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

namespace rsl {

namespace {

// Union-find with path halving.
int find_root(std::vector<int>& parent, int i) {
    while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
    return i;
}

struct PositionHash {
    size_t operator()(const Vec3& p) const {
        const std::hash<float> h;
        return h(p.x) ^ (h(p.y) * 0x9e3779b97f4a7c15ull) ^ (h(p.z) * 0xc2b2ae3d27d4eb4full);
    }
};

}  // namespace

const Vec3* SolidPieces::probe_directions() {
    static const std::array<Vec3, kProbes> directions = [] {
        const Mat3 turn = Mat3(glm::rotate(Mat4(1.0f), 0.1f, glm::normalize(Vec3(1, 2, 3))));
        std::array<Vec3, kProbes> d;
        for (int k = 0; k < kProbes; ++k) {
            const Vec3 axis_or_diagonal =
                k < 6 ? Vec3(k == 0 ? 1 : k == 1 ? -1 : 0, k == 2 ? 1 : k == 3 ? -1 : 0, k == 4 ? 1 : k == 5 ? -1 : 0)
                      : glm::normalize(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
            d[size_t(k)] = turn * axis_or_diagonal;
        }
        return d;
    }();
    return directions.data();
}

SolidPieces::SolidPieces(const TriangleMesh& mesh, const std::optional<Vec3>& only_around) {
    whole_.add_instance(whole_.add_mesh(mesh), Mat4(1.0f));
    whole_.commit();
    // Vertices at one position are one vertex (a seam of the UVs or normals).
    std::unordered_map<Vec3, int, PositionHash> welded;
    std::vector<int> weld(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        weld[v] = welded.try_emplace(mesh.positions[v], int(welded.size())).first->second;
    // Triangles sharing an edge are one piece; pieces that only touch at a
    // vertex (a cone's tip on a box's face) stay two.
    const size_t triangles = mesh.triangle_count();
    std::vector<int> parent(triangles);
    std::iota(parent.begin(), parent.end(), 0);
    struct EdgeUse {
        int first_triangle;
        int uses;
    };
    std::unordered_map<uint64_t, EdgeUse> edges;
    for (size_t t = 0; t < triangles; ++t)
        for (int c = 0; c < 3; ++c) {
            const uint32_t a = uint32_t(weld[mesh.indices[3 * t + size_t(c)]]);
            const uint32_t b = uint32_t(weld[mesh.indices[3 * t + size_t((c + 1) % 3)]]);
            auto [it, added] = edges.try_emplace(uint64_t(std::min(a, b)) << 32 | std::max(a, b), EdgeUse{int(t), 0});
            ++it->second.uses;
            if (!added) {
                const int r0 = find_root(parent, it->second.first_triangle), r1 = find_root(parent, int(t));
                if (r0 != r1) parent[size_t(r1)] = r0;
            }
        }
    // A piece with an edge of one triangle (or three) has a hole: it
    // encloses nothing, however the probes fall (a cup's inside).
    std::unordered_map<int, bool> closed;  // per root triangle
    for (const auto& [edge, use] : edges)
        closed.try_emplace(find_root(parent, use.first_triangle), true).first->second &= use.uses % 2 == 0;
    std::unordered_map<int, TriangleMesh> by_root;
    for (size_t t = 0; t < triangles; ++t) {
        const int root = find_root(parent, int(t));
        if (!closed[root]) continue;
        TriangleMesh& piece = by_root[root];
        for (int c = 0; c < 3; ++c) {
            piece.indices.push_back(uint32_t(piece.positions.size()));
            piece.positions.push_back(mesh.positions[mesh.indices[3 * t + size_t(c)]]);
        }
    }
    // Pieces in a fixed order (their first triangle's), so bakes repeat.
    std::vector<std::pair<Vec3, TriangleMesh*>> order;
    for (auto& [root, piece] : by_root) order.emplace_back(piece.positions[0], &piece);
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
        return std::tie(a.first.x, a.first.y, a.first.z) < std::tie(b.first.x, b.first.y, b.first.z);
    });
    for (const auto& [first, piece_mesh] : order) {
        auto piece = std::make_unique<Piece>();
        piece->lo = Vec3(1e30f), piece->hi = Vec3(-1e30f);
        double volume = 0.0;  // six times the signed volume
        for (size_t i = 0; i < piece_mesh->positions.size(); i += 3) {
            const glm::dvec3 p0(piece_mesh->positions[i]), p1(piece_mesh->positions[i + 1]),
                p2(piece_mesh->positions[i + 2]);
            volume += glm::dot(p0, glm::cross(p1, p2));
        }
        for (const Vec3& p : piece_mesh->positions) piece->lo = glm::min(piece->lo, p), piece->hi = glm::max(piece->hi, p);
        // Faces turned inwards: a room's walls seen from inside, not a solid.
        if (!(volume > 0.0)) continue;
        if (only_around && (glm::any(glm::lessThan(*only_around, piece->lo)) ||
                            glm::any(glm::greaterThan(*only_around, piece->hi))))
            continue;
        piece->scene.add_instance(piece->scene.add_mesh(*piece_mesh), Mat4(1.0f));
        piece->scene.commit();
        pieces_.push_back(std::move(piece));
    }
}

SolidPieces::~SolidPieces() = default;

namespace {

// Every probe meets the mesh and nearly all from behind.
bool probes_meet_from_behind(const RayScene& scene, const Vec3& point) {
    const Vec3* directions = SolidPieces::probe_directions();
    int from_behind = 0;
    for (int k = 0; k < SolidPieces::kProbes; ++k) {
        const RayHit hit = scene.intersect(point, directions[k]);
        if (!hit.hit) return false;  // escapes
        from_behind += glm::dot(hit.geometric_normal, directions[k]) > 0.0f;
    }
    return from_behind >= SolidPieces::kProbes - 2;
}

}  // namespace

SolidPieces::Probe SolidPieces::probe(const Vec3& point) const {
    Probe result;
    const Vec3* directions = probe_directions();
    int from_behind = 0;
    for (int k = 0; k < kProbes; ++k) {
        const RayHit hit = whole_.intersect(point, directions[k]);
        if (!hit.hit) continue;
        result.nearest = std::min(result.nearest, hit.t);
        from_behind += glm::dot(hit.geometric_normal, directions[k]) > 0.0f;
    }
    // Probes may escape through small holes (a teapot's spout and handle,
    // open where they meet the body): nearly all leaving from behind decides.
    result.inside = from_behind >= kProbes - 2;
    for (size_t p = 0; p < pieces_.size() && !result.inside; ++p) {
        const Piece& piece = *pieces_[p];
        if (glm::any(glm::lessThan(point, piece.lo)) || glm::any(glm::greaterThan(point, piece.hi))) continue;
        result.inside = probes_meet_from_behind(piece.scene, point);
    }
    return result;
}

}  // namespace rsl
