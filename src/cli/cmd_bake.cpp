// `rsl bake SCENE|MESH`: bake (or reuse) the SVDF and OVDF of every part.
#include <fmt/core.h>

#include "fields/field_cache.h"
#include "src/cli/command.h"
#include "src/core/scene.h"

namespace rsl::cli {
namespace {

struct BakeArgs {
    std::string input, output;
    bool svdf_only = false, quiet = false;
    int clusters = 0, vectors = 0, supersampling = 0, ovdf_vectors = 0, cube_resolution = 0, shells = 0;
};

void run_bake(const BakeArgs& args) {
    const Scene scene = load_scene(args.input);
    FieldCacheOptions options = default_field_options(scene);
    if (!args.output.empty()) options.directory = args.output;
    options.svdf_only = args.svdf_only;
    options.verbose = !args.quiet;
    if (args.clusters > 0) options.svdf.clusters = args.clusters;
    if (args.vectors > 0) options.svdf.vectors = args.vectors;
    if (args.supersampling > 0) options.svdf.supersampling = options.ovdf.supersampling = args.supersampling;
    if (args.ovdf_vectors > 0) options.ovdf.vectors = args.ovdf_vectors;
    if (args.cube_resolution > 0) options.ovdf.cube_resolution = args.cube_resolution;
    if (args.shells > 0) options.ovdf.shells = args.shells;
    const auto fields = bake_or_load_fields(scene, options);
    size_t reused = 0, baked = 0;
    for (const PartFields& f : fields) {
        fmt::print("{}\n", f.svdf_file.string());
        (f.svdf_reused ? reused : baked)++;
        if (f.ovdf) {
            fmt::print("{}\n", f.ovdf_file.string());
            (f.ovdf_reused ? reused : baked)++;
        }
    }
    if (!args.quiet) fmt::print(stderr, "rsl bake: {} field files baked, {} reused from the cache\n", baked, reused);
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
        app.add_flag("-q,--quiet", args->quiet, "No progress output (warnings still go to stderr)");
        app.footer(
            "Cache: one .rslf file per part and field kind, named "
            "<scene>.<part index>-<part name>.<svdf|ovdf>.<key>.rslf, where the key hashes the format version, "
            "the part's mesh and the parameters; a change of any of them selects a new file. A run reuses every "
            "cached file that reads back valid (version, mesh, parameters, checksum) and says so; a corrupt or "
            "foreign file is refused with a warning, baked again and replaced. Files are written atomically. "
            "Defaults of the options above come from the scene's \"precompute\" section (docs/SCENE_FORMAT.md). "
            "`rsl info FILE.rslf` checks one file.");
        app.callback([args] { run_bake(*args); });
    }});

}  // namespace
}  // namespace rsl::cli
