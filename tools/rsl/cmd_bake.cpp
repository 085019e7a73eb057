// `rsl bake SCENE|MESH`: bake (or reuse) the SVDF and OVDF of every unique
// mesh, or of one shard of them (--shard I/N).
#include <fmt/core.h>

#include "src/fields/field_cache.h"
#include "tools/rsl/command.h"
#include "tools/rsl/progress_display.h"
#include "tools/rsl/unique_meshes.h"
#include "src/core/scene.h"

namespace rsl::cli {
namespace {

struct BakeArgs {
    std::string input, output, shard;
    bool svdf_only = false, quiet = false;
    int clusters = 0, vectors = 0, supersampling = 0, ovdf_vectors = 0, cube_resolution = 0, shells = 0;
};

void run_bake(const BakeArgs& args) {
    FieldShard shard;
    if (!args.shard.empty()) shard = parse_field_shard(args.shard);  // before the (slow) scene load
    const Scene scene = load_scene(args.input);
    FieldCacheOptions options = default_field_options(scene);
    options.shard = shard;
    if (!args.output.empty()) options.directory = args.output;
    options.svdf_only = args.svdf_only;
    ProgressDisplay display(!args.quiet);
    options.progress = [&display](const std::string& what, double fraction) { display(what, fraction); };
    if (args.clusters > 0) options.svdf.clusters = args.clusters;
    if (args.vectors > 0) options.svdf.vectors = args.vectors;
    if (args.supersampling > 0) options.svdf.supersampling = options.ovdf.supersampling = args.supersampling;
    if (args.ovdf_vectors > 0) options.ovdf.vectors = args.ovdf_vectors;
    if (args.cube_resolution > 0) options.ovdf.cube_resolution = args.cube_resolution;
    if (args.shells > 0) options.ovdf.shells = args.shells;
    const SceneFields fields = bake_or_load_fields(scene, options);
    int files = 0;  // of the whole scene, every shard's
    for (const UniqueFields& u : fields.unique)
        for (const FieldOutcome* o : {&u.svdf_outcome, &u.ovdf_outcome}) {
            files += !o->file.empty();
            if (o->state != FieldState::Skipped) fmt::print("{}\n", o->file.string());
        }
    if (args.quiet) return;
    for (const UniqueFields& u : fields.unique)
        for (const FieldOutcome* o : {&u.svdf_outcome, &u.ovdf_outcome})
            if (o->state == FieldState::Reused)
                display.note(fmt::format("cached {}", o->file.string()));
            else if (o->state == FieldState::Baked)
                display.note(fmt::format("{}: baked in {:.1f} s, 1:{:.1f} compression, rms {:.4f}",
                                         o->file.filename().string(), o->seconds, o->compression_ratio, o->rms_error));
    const int baked = fields.count(FieldState::Baked), reused = fields.count(FieldState::Reused);
    fmt::print(stderr, "rsl bake: {} parts, {} unique mesh{}{}\n", scene.parts.size(), fields.unique.size(),
               fields.unique.size() == 1 ? "" : "es",
               shard.all() ? "" : fmt::format("; shard {}/{}: {} of {} field files", shard.index, shard.count,
                                              baked + reused, files));
    print_unique_meshes(stderr, scene, fields);
    fmt::print(stderr, "rsl bake: {} field files baked, {} reused from the cache\n", baked, reused);
}

RegisterCommand bake_command({"bake",
    "Precompute the visibility fields (SVDF, OVDF) of every part of a scene or mesh; prints the field files",
    30, [](CLI::App& app) {
        auto args = std::make_shared<BakeArgs>();
        app.add_option("input", args->input, "Scene file (.json), glTF, or a single mesh (.obj)")->required();
        app.add_option("-o,--output", args->output,
                       "Cache folder for the field files (default: .rsl-cache beside the input)");
        app.add_flag("--svdf-only", args->svdf_only, "Only self-visibility (no OVDF)");
        app.add_option("--clusters", args->clusters, "SVDF CPCA clusters (default: scene setting, 256)");
        app.add_option("--vectors", args->vectors, "SVDF CPCA vectors per cluster (default: scene setting, 8)");
        app.add_option("--supersampling", args->supersampling, "k×k rays per texel where visibility changes, SVDF and OVDF (default 2)");
        app.add_option("--ovdf-vectors", args->ovdf_vectors, "OVDF PCA vectors per segment (default: scene setting, 8)");
        app.add_option("--cube-resolution", args->cube_resolution, "OVDF sample points per cube-face side (default: scene setting, 32)");
        app.add_option("--shells", args->shells, "OVDF shells around the part (default: scene setting, 16)");
        app.add_option("--shard", args->shard,
                       "I/N: bake only shard I (0 <= I < N) of the unique fields, for N processes or machines "
                       "sharing the cache folder (docs/design/FIELDS.md)");
        app.add_flag("-q,--quiet", args->quiet, "No progress output (warnings still go to stderr)");
        app.footer(
            "Cache: one .rslf file per unique mesh and field kind, named <svdf|ovdf>-<key>.rslf, where the key "
            "hashes the format version, the mesh's content and the parameters: parts that share a mesh (glTF "
            "nodes of one mesh, one OBJ named by several parts) share one file, baked once, and any scene using "
            "that mesh with those parameters finds it; a change of mesh or parameters selects a new file. With "
            "--shard I/N a run bakes only the files whose rank, sorted by name, is I mod N. A run reuses every "
            "cached file that reads back valid (version, mesh, parameters, checksum) and says so; a corrupt or "
            "foreign file is refused with a warning, baked again and replaced. Files are written atomically. "
            "Defaults of the options above come from the scene's \"precompute\" section (docs/SCENE_FORMAT.md). "
            "`rsl info FILE.rslf` checks one file.");
        app.callback([args] { run_bake(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
