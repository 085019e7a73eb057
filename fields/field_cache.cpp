#include "fields/field_cache.h"

#include <cctype>
#include <cstdio>

#include <fmt/format.h>

#include "fields/field_file.h"
#include "fields/progress_report.h"
#include "src/core/error.h"

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

// Reads a cached file if it is there and valid; explains why not otherwise.
template <typename Field, typename Read>
std::optional<Field> try_cached(const fs::path& path, const FieldExpectation& expect, bool verbose, Read read) {
    if (!fs::exists(path)) return std::nullopt;
    try {
        return read(path, expect);
    } catch (const Error& e) {
        if (verbose) std::fprintf(stderr, "rsl bake: rebuilding: %s\n", e.what());
        return std::nullopt;
    }
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
        f.svdf = try_cached<Svdf>(f.svdf_file, {hash, svdf_params}, options.verbose, read_svdf);
        f.svdf_reused = f.svdf.has_value();
        if (!f.svdf) {
            ProgressReport progress("SVDF " + label, options.verbose);
            SvdfBakeStats stats;
            f.svdf = bake_svdf(mesh, options.svdf, &stats, [&](double x) { progress.update(x); });
            write_svdf(f.svdf_file, *f.svdf, hash);
            progress.finish(fmt::format("1:{:.1f} compression, rms {:.4f}", stats.compression.compression_ratio(),
                                        stats.compression.rms_error));
        } else if (options.verbose) {
            std::fprintf(stderr, "SVDF %s: cached %s\n", label.c_str(), f.svdf_file.string().c_str());
        }
        if (options.svdf_only) continue;

        f.ovdf_file = field_path(options, scene, int(i), "ovdf", hash, ovdf_params);
        f.ovdf = try_cached<Ovdf>(f.ovdf_file, {hash, ovdf_params}, options.verbose, read_ovdf);
        f.ovdf_reused = f.ovdf.has_value();
        if (!f.ovdf) {
            ProgressReport progress("OVDF " + label, options.verbose);
            OvdfBakeStats stats;
            f.ovdf = bake_ovdf(mesh, options.ovdf, &stats, [&](double x) { progress.update(x); });
            write_ovdf(f.ovdf_file, *f.ovdf, hash);
            progress.finish(fmt::format("1:{:.1f} compression, rms {:.4f}", stats.compression.compression_ratio(),
                                        stats.compression.rms_error));
        } else if (options.verbose) {
            std::fprintf(stderr, "OVDF %s: cached %s\n", label.c_str(), f.ovdf_file.string().c_str());
        }
    }
    return fields;
}

}  // namespace rsl
