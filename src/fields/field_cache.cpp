#include "src/fields/field_cache.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "src/fields/field_file.h"
#include "src/core/error.h"
#include "src/shading/ovdf_inside.h"

namespace rsl {
namespace fs = std::filesystem;

namespace {

bool same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
    return a.positions == b.positions && a.normals == b.normals && a.tangents == b.tangents && a.indices == b.indices;
}

fs::path cache_file(const fs::path& directory, const char* kind, uint64_t mesh, const std::string& params) {
    uint64_t key = fnv1a64(&kFieldFormatVersion, sizeof(kFieldFormatVersion));
    key = fnv1a64(&mesh, sizeof(mesh), key);
    key = fnv1a64(params.data(), params.size(), key);
    return directory / fmt::format("{}-{:016x}.rslf", kind, key);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

size_t model_bytes(const CpcaModel& m) {
    return m.tables.size() * sizeof(float) + m.assignment.size() * sizeof(int32_t) +
           m.coefficients.size() * sizeof(float);
}

// One field of one unique mesh: read from `out.file` when the file is there
// and valid; otherwise baked (reporting options.progress) and written there. A
// file that is there but refused (corrupt, truncated, foreign) is worth a
// warning even when quiet: it is being replaced. Stale files need none: any
// change of mesh or parameters selects a different file name.
template <typename Field, typename Params, typename Stats>
std::shared_ptr<const Field> load_or_bake(const FieldExpectation& expect, const std::string& label,
                                          const TriangleMesh& mesh, const Params& params,
                                          const FieldCacheOptions& options, FieldOutcome& out, Field (*read)(const fs::path&, const FieldExpectation&),
                                          Field (*bake)(const TriangleMesh&, const Params&, Stats*,
                                                        const std::function<void(double)>&),
                                          void (*write)(const fs::path&, const Field&, uint64_t)) {
    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<const Field> field;
    std::error_code ec;  // a folder that cannot be searched: baked, and its write says why
    if (fs::exists(out.file, ec)) {
        try {
            field = std::make_shared<const Field>(read(out.file, expect));
            out.state = FieldState::Reused;
        } catch (const Error& e) {
            warn("refusing a cached field file, baking it again: {}", e.what());
        }
    }
    if (!field) {
        Stats stats;
        field = std::make_shared<const Field>(bake(mesh, params, &stats, [&](double x) {
            if (options.progress) options.progress(label, x);
        }));
        try {
            write(out.file, *field, *expect.mesh_hash);
        } catch (const Error& e) {
            if (options.on_write_failure == CacheWriteFailure::Fail) throw;
            warn("cannot write the field cache, going on with the field baked in memory: {}", e.what());
        }
        out.state = FieldState::Baked;
        out.compression_ratio = stats.compression.compression_ratio();
        out.rms_error = stats.compression.rms_error;
    }
    if (options.progress) options.progress(label, 1.0);  // baked, or read from the cache
    out.seconds = seconds_since(start);
    const auto disk_bytes = fs::file_size(out.file, ec);
    out.disk_bytes = ec ? 0 : size_t(disk_bytes);  // 0: not written
    out.memory_bytes = memory_bytes(*field);
    return field;
}

}  // namespace

std::vector<MeshInstances> group_instances(const Scene& scene) {
    std::vector<MeshInstances> groups;
    std::map<uint64_t, size_t> group_of_hash;
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const uint64_t hash = mesh_hash(scene.parts[p].mesh);
        const auto [it, inserted] = group_of_hash.emplace(hash, groups.size());
        if (inserted) groups.push_back(MeshInstances{hash, {}});
        MeshInstances& group = groups[it->second];
        if (!inserted) RSL_CHECK(same_mesh(scene.parts[size_t(group.parts.front())].mesh, scene.parts[p].mesh));
        group.parts.push_back(int(p));
    }
    return groups;
}

int SceneFields::count(FieldState state) const {
    int n = 0;
    for (const UniqueFields& u : unique) n += (u.svdf_outcome.state == state) + (u.ovdf_outcome.state == state);
    return n;
}

FieldShard parse_field_shard(const std::string& text, const std::string& option) {
    const auto fail = [&](const std::string& why) -> FieldShard {
        throw_error("{} '{}': {} (expected I/N: shard I of N, integers with 0 <= I < N)", option, text, why);
    };
    const size_t slash = text.find('/');
    if (slash == std::string::npos) return fail("no '/'");
    const auto integer = [&](std::string_view digits, const char* what) {
        int value = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
            fail(fmt::format("{} is not a whole number", what));
        return value;
    };
    const std::string_view all(text);
    FieldShard shard{integer(all.substr(0, slash), "I"), integer(all.substr(slash + 1), "N")};
    if (shard.count < 1) return fail("N must be at least 1");
    if (shard.index < 0 || shard.index >= shard.count) return fail("I must lie in 0 .. N-1");
    return shard;
}

SvdfParams svdf_params_from(const PrecomputeSettings& s) {
    SvdfParams p;
    p.resolution = s.svdf_resolution;
    p.clusters = s.svdf_clusters;
    p.vectors = s.svdf_vectors;
    // The scene's supersampling is rays per texel side everywhere; ours is
    // adaptive (boundary texels only), where 2 already places edges below a
    // texel (docs/design/FIELDS.md).
    p.supersampling = std::max(1, std::min(s.svdf_supersampling, 2));
    return p;
}

OvdfParams ovdf_params_from(const PrecomputeSettings& s) {
    OvdfParams p;
    p.shells = s.ovdf_shells;
    p.inner_radius = s.ovdf_inner_radius;
    p.outer_radius = s.ovdf_outer_radius;
    p.cube_resolution = s.ovdf_cube_resolution;
    p.vdt_resolution = s.ovdf_vdt_resolution;
    p.vectors = s.ovdf_vectors;
    return p;
}

fs::path default_cache_directory(const fs::path& scene_file) {
    const fs::path parent = scene_file.has_parent_path() ? scene_file.parent_path() : fs::path(".");
    return parent / ".rsl-cache";
}

FieldCacheOptions default_field_options(const Scene& scene) {
    FieldCacheOptions o;
    o.directory = default_cache_directory(scene.source);
    o.svdf = svdf_params_from(scene.precompute);
    o.ovdf = ovdf_params_from(scene.precompute);
    return o;
}

fs::path svdf_cache_file(const fs::path& directory, uint64_t mesh_hash, const SvdfParams& params) {
    return cache_file(directory, "svdf", mesh_hash, params_json(params));
}

fs::path ovdf_cache_file(const fs::path& directory, uint64_t mesh_hash, const OvdfParams& params) {
    // The radial spans' resolution is the build's, not a parameter: a build
    // that bakes finer spans looks for files of its own.
    return cache_file(directory, "ovdf", mesh_hash,
                      params_json(params) + fmt::format(";spans {}", shading::kOvdfSpanResolution));
}

size_t memory_bytes(const Svdf& svdf) { return model_bytes(svdf.model); }

size_t memory_bytes(const Ovdf& ovdf) {
    const OvdfParams& p = ovdf.params;
    const size_t frames = size_t(6) * size_t(p.cube_resolution) * size_t(p.cube_resolution);
    return model_bytes(ovdf.model) + (ovdf.surface_distance.size() + ovdf.radial_span.size()) * sizeof(float) +
           frames * sizeof(Frame) +
           size_t(p.shells) * (sizeof(float) + sizeof(OvdfZoom));
}

SceneFields plan_fields(const Scene& scene, const FieldCacheOptions& given) {
    FieldCacheOptions options = given;
    if (options.directory.empty()) options.directory = default_cache_directory(scene.source);
    RSL_CHECK(options.shard.count >= 1 && options.shard.index >= 0 && options.shard.index < options.shard.count);
    SceneFields result;
    result.unique_of_part.assign(scene.parts.size(), -1);
    std::vector<FieldOutcome*> outcomes;
    for (MeshInstances& group : group_instances(scene)) {
        for (int p : group.parts) result.unique_of_part[size_t(p)] = int(result.unique.size());
        UniqueFields& u = result.unique.emplace_back();
        u.mesh = std::move(group);
        u.svdf_outcome.file = svdf_cache_file(options.directory, u.mesh.mesh_hash, options.svdf);
        if (!options.svdf_only) {
            // The name and the file hold the radius used, so a stale one is refused as any other.
            u.ovdf_params = ovdf_params_for_mesh(options.ovdf, scene.parts[size_t(u.mesh.parts.front())].mesh);
            u.ovdf_outcome.file = ovdf_cache_file(options.directory, u.mesh.mesh_hash, u.ovdf_params);
        }
    }
    for (UniqueFields& u : result.unique)
        for (FieldOutcome* o : {&u.svdf_outcome, &u.ovdf_outcome})
            if (!o->file.empty()) outcomes.push_back(o);
    // The shard's share: the files in order of their names, every count-th
    // from index on. Names, not scene order, so that the share depends only
    // on which (mesh, parameters) the scene holds.
    std::sort(outcomes.begin(), outcomes.end(),
              [](const FieldOutcome* a, const FieldOutcome* b) { return a->file.filename() < b->file.filename(); });
    for (size_t rank = 0; rank < outcomes.size(); ++rank)
        outcomes[rank]->wanted = int(rank % size_t(options.shard.count)) == options.shard.index;
    return result;
}

SceneFields bake_or_load_fields(const Scene& scene, const FieldCacheOptions& options) {
    SceneFields result = plan_fields(scene, options);
    const std::string svdf_params = params_json(options.svdf);
    for (size_t m = 0; m < result.unique.size(); ++m) {
        UniqueFields& u = result.unique[m];
        const Part& first = scene.parts[size_t(u.mesh.parts.front())];
        const std::string label = fmt::format("mesh {}/{} '{}' ({} vertices, {} part{})", m + 1, result.unique.size(),
                                              first.name, first.mesh.vertex_count(), u.mesh.parts.size(),
                                              u.mesh.parts.size() == 1 ? "" : "s");
        const uint64_t hash = u.mesh.mesh_hash;
        if (u.svdf_outcome.wanted)
            u.svdf = load_or_bake({hash, svdf_params}, "SVDF " + label, first.mesh, options.svdf, options,
                                  u.svdf_outcome, read_svdf, bake_svdf, write_svdf);
        if (u.ovdf_outcome.wanted)
            u.ovdf = load_or_bake({hash, params_json(u.ovdf_params)}, "OVDF " + label, first.mesh, u.ovdf_params, options,
                                  u.ovdf_outcome, read_ovdf, bake_ovdf, write_ovdf);
    }
    return result;
}

}  // namespace rsl
