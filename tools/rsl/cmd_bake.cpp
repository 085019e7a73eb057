// `rsl bake SCENE|MESH`: bake (or reuse) the SVDF and OVDF of every unique
// mesh, or of one shard of them (--shard I/N).
#include <optional>
#include <vector>

#include <fmt/core.h>

#include "src/core/error.h"
#include "src/core/precompute_limits.h"
#include "src/fields/field_cache.h"
#include "src/fields/field_file.h"
#include "tools/rsl/command.h"
#include "tools/rsl/progress_display.h"
#include "tools/rsl/unique_meshes.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"

namespace rsl::cli {
namespace {

struct BakeArgs {
    std::string input, output, shard;
    bool svdf_only = false, quiet = false;
    // Absent: the scene's setting; given, checked by the scene file's rules.
    std::optional<int> clusters, vectors, supersampling, ovdf_vectors, cube_resolution, shells;
};

struct BakeFlag {
    const char* name;
    std::optional<int> value;
    int PrecomputeSettings::*setting;
};

std::vector<BakeFlag> bake_flags(const BakeArgs& args) {
    return {{"--clusters", args.clusters, &PrecomputeSettings::svdf_clusters},
            {"--vectors", args.vectors, &PrecomputeSettings::svdf_vectors},
            {"--supersampling", args.supersampling, &PrecomputeSettings::svdf_supersampling},
            {"--ovdf-vectors", args.ovdf_vectors, &PrecomputeSettings::ovdf_vectors},
            {"--cube-resolution", args.cube_resolution, &PrecomputeSettings::ovdf_cube_resolution},
            {"--shells", args.shells, &PrecomputeSettings::ovdf_shells}};
}

// The flags' values checked one at a time on the scene's (valid) settings
// by the rules and messages of a scene file's "precompute" section, so that
// the first problem names the flag that made it.
void check_bake_flags(const BakeArgs& args, const PrecomputeSettings& scene) {
    PrecomputeSettings settings = scene;
    for (const BakeFlag& flag : bake_flags(args)) {
        if (!flag.value) continue;
        settings.*flag.setting = *flag.value;
        if (const auto problem = precompute_problem(settings))
            throw_error("{} {}: {} (as precompute.{} in a scene file)", flag.name, *flag.value, problem->message,
                        problem->key);
    }
}

// The flags that make this bake's fields other than the ones `rsl render`
// of the scene looks for ("--vectors 4 (the scene's 8)"); empty when none do.
std::string flags_render_will_not_use(const BakeArgs& args, const Scene& scene, const FieldCacheOptions& baked) {
    const FieldCacheOptions render = default_field_options(scene);
    const bool svdf_differs = params_json(baked.svdf) != params_json(render.svdf);
    const bool ovdf_differs = !baked.svdf_only && params_json(baked.ovdf) != params_json(render.ovdf);
    if (!svdf_differs && !ovdf_differs) return "";
    std::string list;
    for (const BakeFlag& flag : bake_flags(args))
        if (flag.value)
            list += fmt::format("{}{} {} (the scene's {})", list.empty() ? "" : ", ", flag.name, *flag.value,
                                scene.precompute.*flag.setting);
    return list;
}

void run_bake(const BakeArgs& args) {
    FieldShard shard;
    if (!args.shard.empty()) shard = parse_field_shard(args.shard);  // before the (slow) scene load
    const Scene scene = load_scene(args.input);
    check_bake_flags(args, scene.precompute);
    FieldCacheOptions options = default_field_options(scene);
    options.shard = shard;
    if (!args.output.empty()) options.directory = args.output;
    options.svdf_only = args.svdf_only;
    ProgressDisplay display(!args.quiet);
    options.progress = [&display](const std::string& what, double fraction) { display(what, fraction); };
    if (args.clusters) options.svdf.clusters = *args.clusters;
    if (args.vectors) options.svdf.vectors = *args.vectors;
    if (args.supersampling) options.svdf.supersampling = options.ovdf.supersampling = *args.supersampling;
    if (args.ovdf_vectors) options.ovdf.vectors = *args.ovdf_vectors;
    if (args.cube_resolution) options.ovdf.cube_resolution = *args.cube_resolution;
    if (args.shells) options.ovdf.shells = *args.shells;
    // Before the bake, which may take hours: the user can stop and edit the scene instead.
    if (const std::string flags = flags_render_will_not_use(args, scene, options); !flags.empty())
        fmt::print(stderr,
                   "rsl bake: note: {} bake fields that `rsl render` of this scene will not use: it looks for "
                   "fields of the scene's \"precompute\" settings (docs/SCENE_FORMAT.md); set them there instead\n",
                   flags);
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
