#include "fields/field_cache.h"

#include <cctype>
#include <cstdio>

#include <fmt/format.h>

#include "fields/field_file.h"
#include "src/core/error.h"
#include "src/core/progress_report.h"

namespace rsl {
namespace fs = std::filesystem;

namespace {

std::string safe_name(const std::string& name) {
    std::string out;
    for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out.empty() ? "part" : out;
}

fs::path field_path(const FieldCacheOptions& options, const Scene& scene, int part, const char* kind,
                    uint64_t mesh, const std::string& params) {
    uint64_t key = fnv1a64(&kFieldFormatVersion, sizeof(kFieldFormatVersion));
    key = fnv1a64(&mesh, sizeof(mesh), key);
    key = fnv1a64(params.data(), params.size(), key);
    const std::string stem = scene.source.empty() ? safe_name(scene.name) : safe_name(scene.source.stem().string());
    return options.directory /
           fmt::format("{}.{}-{}.{}.{:016x}.rslf", stem, part, safe_name(scene.parts[part].name), kind, key);
}

// One field of one part: read from `path` when the file is there and valid;
// otherwise baked (with progress on stderr) and written there. A file that is
// there but refused (corrupt, truncated, foreign) is worth a warning even
// when quiet: it is being replaced. Stale files need none: any change of mesh
// or parameters selects a different file name.
template <typename Field, typename Params, typename Stats>
Field load_or_bake(const fs::path& path, const FieldExpectation& expect, const std::string& label,
                   const TriangleMesh& mesh, const Params& params, const FieldCacheOptions& options, bool& reused,
                   Field (*read)(const fs::path&, const FieldExpectation&),
                   Field (*bake)(const TriangleMesh&, const Params&, Stats*, const std::function<void(double)>&),
                   void (*write)(const fs::path&, const Field&, uint64_t)) {
    reused = false;
    const bool verbose = options.verbose;
    if (fs::exists(path)) {
        try {
            Field field = read(path, expect);
            reused = true;
            if (verbose) std::fprintf(stderr, "%s: cached %s\n", label.c_str(), path.string().c_str());
            if (options.progress) options.progress(label, 1.0);
            return field;
        } catch (const Error& e) {
            warn("refusing a cached field file, baking it again: {}", e.what());
        }
    }
    ProgressReport progress(label, verbose);
    Stats stats;
    Field field = bake(mesh, params, &stats, [&](double x) {
        progress.update(x);
        if (options.progress) options.progress(label, x);
    });
    write(path, field, *expect.mesh_hash);
    if (options.progress) options.progress(label, 1.0);
    progress.finish(fmt::format("1:{:.1f} compression, rms {:.4f}", stats.compression.compression_ratio(),
                                stats.compression.rms_error));
    return field;
}

}  // namespace

SvdfParams svdf_params_from(const PrecomputeSettings& s) {
    SvdfParams p;
    p.resolution = s.svdf_resolution;
    p.clusters = s.svdf_clusters;
    p.vectors = s.svdf_vectors;
    // The scene's supersampling is rays per texel side everywhere; ours is
    // adaptive (boundary texels only), where 2 already places edges below a
    // texel (docs/FIELDS.md).
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

std::vector<PartFields> bake_or_load_fields(const Scene& scene, const FieldCacheOptions& given) {
    FieldCacheOptions options = given;
    if (options.directory.empty()) options.directory = default_cache_directory(scene.source);
    std::vector<PartFields> fields(scene.parts.size());
    const std::string svdf_params = params_json(options.svdf), ovdf_params = params_json(options.ovdf);
    for (size_t i = 0; i < scene.parts.size(); ++i) {
        const TriangleMesh& mesh = scene.parts[i].mesh;
        const uint64_t hash = mesh_hash(mesh);
        PartFields& f = fields[i];
        const std::string label = fmt::format("part {}/{} '{}' ({} vertices)", i + 1, scene.parts.size(),
                                              scene.parts[i].name, mesh.vertex_count());

        f.svdf_file = field_path(options, scene, int(i), "svdf", hash, svdf_params);
        f.svdf = load_or_bake(f.svdf_file, {hash, svdf_params}, "SVDF " + label, mesh, options.svdf, options,
                              f.svdf_reused, read_svdf, bake_svdf, write_svdf);
        if (options.svdf_only) continue;
        f.ovdf_file = field_path(options, scene, int(i), "ovdf", hash, ovdf_params);
        f.ovdf = load_or_bake(f.ovdf_file, {hash, ovdf_params}, "OVDF " + label, mesh, options.ovdf, options,
                              f.ovdf_reused, read_ovdf, bake_ovdf, write_ovdf);
    }
    return fields;
}

}  // namespace rsl
