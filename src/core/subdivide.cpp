// Long-edge splitting (red-green refinement, repeated until no edge is long).
#include "src/core/subdivide.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "src/core/checksum.h"
#include "src/core/error.h"
#include "src/core/memory_limit.h"
#include "src/core/scene.h"

namespace rsl {
namespace {

// Builds the midpoint vertices of one pass: one per (unordered) vertex pair.
class MidpointMaker {
public:
    explicit MidpointMaker(TriangleMesh& mesh) : mesh_(mesh) {}

    uint32_t operator()(uint32_t a, uint32_t b, const Vec3& face_normal) {
        const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        const auto [it, inserted] = midpoints_.try_emplace(key, uint32_t(mesh_.positions.size()));
        if (inserted) append(a, b, face_normal);
        return it->second;
    }

private:
    // (x + y)·½ is symmetric in IEEE arithmetic, so the two copies of a
    // crease edge (other indices, same positions) get bit-equal midpoints.
    template <typename T>
    static T mean(const T& x, const T& y) {
        return (x + y) * 0.5f;
    }

    void append(uint32_t a, uint32_t b, const Vec3& face_normal) {
        TriangleMesh& m = mesh_;
        m.positions.push_back(mean(m.positions[a], m.positions[b]));
        // Opposite endpoint normals (a knife edge) have no mean: the face's normal stands in.
        Vec3 n = m.normals[a] + m.normals[b];
        n = glm::dot(n, n) > 1e-12f ? glm::normalize(n) : face_normal;
        m.normals.push_back(n);
        if (!m.tangents.empty()) {
            const Vec4 ta = m.tangents[a];  // a copy: emplace_back may reallocate under a reference
            const Frame frame = Frame::from_normal_tangent(n, Vec3(ta) + Vec3(m.tangents[b]));
            m.tangents.emplace_back(frame.x, ta.w);
        }
        if (!m.texcoords.empty()) m.texcoords.push_back(mean(m.texcoords[a], m.texcoords[b]));
    }

    TriangleMesh& mesh_;
    std::unordered_map<uint64_t, uint32_t> midpoints_;
};

float squared_length(const Vec3& v) { return glm::dot(v, v); }

// Triangles after refinement, about: an edge k halvings over the target
// makes its triangle 4^k (later passes split the few edges the first ones
// leave long). Counted before anything is allocated.
double estimated_triangles(const TriangleMesh& mesh, float target_edge) {
    double total = 0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const Vec3 &a = mesh.positions[mesh.indices[t]], &b = mesh.positions[mesh.indices[t + 1]],
                   &c = mesh.positions[mesh.indices[t + 2]];
        const double longest = std::sqrt(double(std::max({squared_length(b - a), squared_length(c - b),
                                                          squared_length(a - c)})));
        const double halvings = longest > target_edge ? std::ceil(std::log2(longest / target_edge)) : 0.0;
        total += std::pow(4.0, std::min(halvings, 40.0));
    }
    return total;
}

// One pass: every edge longer than the target is split; returns false when none was.
bool split_long_edges_once(TriangleMesh& mesh, float target_edge) {
    const float target2 = target_edge * target_edge;
    MidpointMaker midpoint(mesh);
    std::vector<uint32_t> out;
    out.reserve(mesh.indices.size() * 2);
    bool split_any = false;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const std::array<uint32_t, 3> v{mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        // Positions by value: the midpoint maker grows the position array.
        const std::array<Vec3, 3> p{mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        std::array<bool, 3> is_long{};  // edge e runs from corner e to corner e + 1
        int long_count = 0;
        for (int e = 0; e < 3; ++e) long_count += is_long[e] = squared_length(p[(e + 1) % 3] - p[e]) > target2;
        if (long_count == 0) {
            out.insert(out.end(), v.begin(), v.end());
            continue;
        }
        split_any = true;
        const Vec3 face_normal = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
        auto mid = [&](int e) { return midpoint(v[e], v[(e + 1) % 3], face_normal); };
        auto emit = [&](uint32_t a, uint32_t b, uint32_t c) { out.insert(out.end(), {a, b, c}); };
        if (long_count == 3) {
            const uint32_t m0 = mid(0), m1 = mid(1), m2 = mid(2);
            emit(v[0], m0, m2), emit(m0, v[1], m1), emit(m2, m1, v[2]), emit(m0, m1, m2);
        } else if (long_count == 1) {
            // Rotated so that the long edge runs a → b.
            const int e = is_long[0] ? 0 : is_long[1] ? 1 : 2;
            const uint32_t a = v[e], b = v[(e + 1) % 3], c = v[(e + 2) % 3], m = mid(e);
            emit(a, m, c), emit(m, b, c);
        } else {
            // Rotated so that a → b and b → c are long and c → a is not.
            const int e = !is_long[2] ? 0 : !is_long[0] ? 1 : 2;
            const uint32_t a = v[e], b = v[(e + 1) % 3], c = v[(e + 2) % 3];
            const uint32_t mab = mid(e), mbc = mid((e + 1) % 3);
            emit(mab, b, mbc);
            // The quad a, mab, mbc, c is cut along its shorter diagonal (better-shaped triangles).
            const Vec3 pa = mesh.positions[a], pc = mesh.positions[c];
            if (squared_length(mesh.positions[mbc] - pa) <= squared_length(pc - mesh.positions[mab]))
                emit(a, mab, mbc), emit(a, mbc, c);
            else
                emit(a, mab, c), emit(mab, mbc, c);
        }
    }
    mesh.indices.swap(out);
    return split_any;
}

}  // namespace

float SubdivisionSettings::target_edge(const TriangleMesh& mesh) const {
    return absolute_edge > 0 ? absolute_edge : relative_edge * mesh.bounding_sphere().radius;
}

size_t subdivide_long_edges(TriangleMesh& mesh, float target_edge, const std::filesystem::path& source) {
    RSL_CHECK_GT(target_edge, 0.0f);
    const double estimate = estimated_triangles(mesh, target_edge);
    if (estimate > double(kMaxSubdividedTriangles))
        throw_file_error(source,
                         "mesh '{}': subdividing to edges of {} would make about {:.3g} triangles (at most {}); "
                         "raise the scene file's subdivision edge or turn subdivision off",
                         mesh.name, target_edge, estimate, kMaxSubdividedTriangles);
    const size_t before = mesh.vertex_count();
    // Each pass halves the long edges and the edges it creates are no longer
    // than the longest one split (a median is shorter than the longer of the
    // sides it lies between), so the longest edge halves every pass or two.
    while (split_long_edges_once(mesh, target_edge)) {
    }
    return mesh.vertex_count() - before;
}

size_t subdivide_for_shading(TriangleMesh& mesh, const SubdivisionSettings& settings,
                             const std::filesystem::path& source) {
    if (!settings.enabled) return 0;
    const float target = settings.target_edge(mesh);
    // A tiny relative_edge times a tiny part can round to 0.
    if (!(target > 0))
        throw_file_error(source, "mesh '{}': the subdivision target edge rounds to {} (raise the scene file's subdivision edge)",
                         mesh.name, target);
    return subdivide_long_edges(mesh, target, source);
}

namespace {

uint64_t geometry_hash(const TriangleMesh& m) {
    uint64_t h = fnv1a64(m.positions.data(), m.positions.size() * sizeof(Vec3));
    h = fnv1a64(m.normals.data(), m.normals.size() * sizeof(Vec3), h);
    h = fnv1a64(m.tangents.data(), m.tangents.size() * sizeof(Vec4), h);
    h = fnv1a64(m.texcoords.data(), m.texcoords.size() * sizeof(Vec2), h);
    return fnv1a64(m.indices.data(), m.indices.size() * sizeof(uint32_t), h);
}

bool same_geometry(const TriangleMesh& a, const TriangleMesh& b) {
    return a.positions == b.positions && a.normals == b.normals && a.tangents == b.tangents &&
           a.texcoords == b.texcoords && a.indices == b.indices;
}

}  // namespace

void subdivide_scene_parts(Scene& scene) {
    // Parts that instance one mesh are subdivided once, and the scene's total
    // is checked against the memory limit before the copies are made.
    std::unordered_map<uint64_t, std::vector<size_t>> firsts_by_hash;  // geometry hash → its first parts
    std::vector<size_t> source_of(scene.parts.size());                 // the first part of the same geometry
    size_t total_vertices = 0;
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        Part& part = scene.parts[p];
        part.loaded_vertices = part.mesh.vertex_count();
        std::vector<size_t>& firsts = firsts_by_hash[geometry_hash(part.mesh)];
        const auto same = std::find_if(firsts.begin(), firsts.end(), [&](size_t q) {
            return scene.parts[q].loaded_vertices == part.loaded_vertices &&
                   same_geometry(scene.parts[q].mesh, part.mesh);
        });
        source_of[p] = same != firsts.end() ? *same : p;
        if (same == firsts.end()) firsts.push_back(p);
    }
    for (size_t p = 0; p < scene.parts.size(); ++p)
        // A skinned segment's vertices carry joints and weights: it loads as it is (docs/SCENE_FORMAT.md, "Skins").
        if (source_of[p] == p && !scene.parts[p].skin)
            subdivide_for_shading(scene.parts[p].mesh, scene.subdivision, scene.source);
    for (size_t p = 0; p < scene.parts.size(); ++p) total_vertices += scene.parts[source_of[p]].mesh.vertex_count();
    check_memory_estimate(kMeshBytesPerVertex * total_vertices + kMeshBytesPerPart * scene.parts.size(),
                          scene.source,
                          fmt::format("{} vertices after subdivision in {} parts", total_vertices, scene.parts.size()));
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        if (source_of[p] == p || scene.parts[p].skin) continue;
        TriangleMesh& mesh = scene.parts[p].mesh;
        const TriangleMesh& from = scene.parts[source_of[p]].mesh;
        mesh.positions = from.positions, mesh.normals = from.normals, mesh.tangents = from.tangents;
        mesh.texcoords = from.texcoords, mesh.indices = from.indices;
    }
}

}  // namespace rsl
