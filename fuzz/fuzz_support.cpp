#include "fuzz/fuzz_support.h"

#include <cmath>
#include <fstream>

#include <unistd.h>

namespace rsl::fuzz {
namespace fs = std::filesystem;

namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const Quat& q) { return std::isfinite(q.w) && finite(Vec3(q.x, q.y, q.z)); }
bool near_unit(const Vec3& v) { return std::abs(glm::dot(v, v) - 1.0f) < 1e-4f; }

template <typename Track>
void check_track(const Track& track, const char* what) {
    const size_t per_key = track.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (track.times.empty() || track.values.size() != per_key * track.times.size())
        finding("{} track: {} values for {} key times", what, track.values.size(), track.times.size());
    for (size_t k = 0; k < track.times.size(); ++k)
        if (!std::isfinite(track.times[k]) || (k > 0 && track.times[k] < track.times[k - 1]))
            finding("{} track: key time {} ({}) is not finite and increasing", what, k, track.times[k]);
    for (const auto& value : track.values)
        if (!finite(value)) finding("{} track: a non-finite value", what);
}

}  // namespace

const fs::path& scratch_dir() {
    static const struct Scratch {
        fs::path dir = fs::temp_directory_path() / fmt::format("rsl_fuzz_{}", ::getpid());
        Scratch() { fs::create_directories(dir); }
        ~Scratch() {
            std::error_code ignored;
            fs::remove_all(dir, ignored);
        }
    } scratch;
    return scratch.dir;
}

fs::path write_input(const uint8_t* data, size_t size, const std::string& extension) {
    const fs::path path = scratch_dir() / ("input" + extension);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) finding("cannot write the input to {}", path.string());
    return path;
}

fs::path write_input(const std::string& bytes, const std::string& extension) {
    return write_input(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), extension);
}

void report_finding(const std::string& message) {
    std::fprintf(stderr, "rsl fuzz finding: %s\n", message.c_str());
    std::fflush(stderr);
    std::abort();
}

void silence_warnings() {
    static const bool once = [] {
        set_warning_handler([](const std::string&) {});
        return true;
    }();
    (void)once;
}

void check_mesh(const TriangleMesh& mesh) {
    const size_t n = mesh.vertex_count();
    RSL_FUZZ_EXPECT(n > 0 && !mesh.indices.empty() && mesh.indices.size() % 3 == 0);
    for (uint32_t i : mesh.indices)
        if (i >= n) finding("mesh '{}': index {} for {} vertices", mesh.name, i, n);
    if (mesh.normals.size() != n || mesh.tangents.size() != n)
        finding("mesh '{}': {} normals, {} tangents for {} vertices", mesh.name, mesh.normals.size(),
                mesh.tangents.size(), n);
    for (size_t v = 0; v < n; ++v) {
        const Vec3& p = mesh.positions[v];
        const Vec3& normal = mesh.normals[v];
        const Vec4& t = mesh.tangents[v];
        const Vec3 tangent(t);
        if (!finite(p)) finding("mesh '{}': vertex {} at ({}, {}, {})", mesh.name, v, p.x, p.y, p.z);
        if (!finite(normal) || !near_unit(normal))
            finding("mesh '{}': vertex {} has normal ({}, {}, {}), not a unit vector", mesh.name, v, normal.x,
                    normal.y, normal.z);
        if (!finite(tangent) || !near_unit(tangent) || std::abs(glm::dot(tangent, normal)) > 1e-3f ||
            std::abs(t.w) != 1.0f)
            finding("mesh '{}': vertex {} has tangent ({}, {}, {}, {}) for normal ({}, {}, {})", mesh.name, v, t.x,
                    t.y, t.z, t.w, normal.x, normal.y, normal.z);
    }
}

void check_scene(const Scene& scene) {
    RSL_FUZZ_EXPECT(!scene.parts.empty());
    const int nodes = int(scene.nodes.size());
    for (int n = 0; n < nodes; ++n) {
        const SceneNode& node = scene.nodes[n];
        int steps = 0;
        for (int p = node.parent; p >= 0; p = scene.nodes[p].parent) {
            if (p >= nodes) finding("node {}: ancestor {} of {} nodes", n, p, nodes);
            if (++steps > nodes) finding("node {} is its own ancestor", n);
        }
        if (node.translation) check_track(*node.translation, "translation");
        if (node.rotation) check_track(*node.rotation, "rotation");
        if (node.scale) check_track(*node.scale, "scale");
    }
    for (const LocalLight& light : scene.lights)
        if (light.path) check_track(*light.path, "light path");
    if (scene.camera.position_path) check_track(*scene.camera.position_path, "camera path");
    if (scene.camera.target_path) check_track(*scene.camera.target_path, "camera targets");
    for (const Part& part : scene.parts) {
        if (part.node < 0 || part.node >= nodes) finding("part '{}': node {} of {}", part.name, part.node, nodes);
        if (part.material < 0 || size_t(part.material) >= scene.materials.size())
            finding("part '{}': material {} of {}", part.name, part.material, scene.materials.size());
        check_mesh(part.mesh);
    }
    // Posing reads every track: before, at and after the animation's range.
    for (const float t : {scene.animation.start - 1, scene.animation.start, scene.animation.end,
                          scene.animation.end + 1})
        for (size_t p = 0; p < scene.parts.size(); ++p) (void)scene.part_transform_at(int(p), t);
}

}  // namespace rsl::fuzz
