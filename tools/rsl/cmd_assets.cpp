// `rsl assets`: generates the project's own assets (robot, kitchen, ground,
// environments) so a fresh clone has everything the default scenes use.
#include <fmt/core.h>

#include "tools/assets/generate_all.h"
#include "tools/assets/yard.h"
#include "tools/rsl/command.h"

namespace rsl::cli {
namespace {

void setup_assets(CLI::App& app) {
    auto out = std::make_shared<std::string>("assets/generated");
    auto force = std::make_shared<bool>(false);
    auto yards = std::make_shared<std::vector<int>>();
    app.add_option("--out", *out, "Folder to write the assets into")->capture_default_str();
    app.add_flag("--force", *force, "Regenerate even when the folder's stamp matches this generator version");
    app.add_option("--yard", *yards,
                   "Also write the scale scenes yard-N.glb and yard-N.json for each N (e.g. --yard 8,128,1024): N\n"
                   "instances of four small meshes bouncing, tumbling and orbiting on a ground")
        ->delimiter(',')
        ->check(CLI::Range(1, assets::kYardMaxInstances));
    app.footer(fmt::format(
        "Writes robot.glb (12 parts, walk loop), ground.obj, kitchen.glb (5 parts), and sunsky/studio/overcast\n"
        "lat-long environments as .exr with .png previews, then OUT/{} holding the generator version ({}).\n"
        "Does nothing when that stamp is current. See assets/README.md.",
        assets::kStampName, assets::kAssetsVersion));
    app.callback([out, force, yards] {
        const assets::GenerateReport report = assets::generate_assets(*out, *force);
        if (!report.regenerated) {
            fmt::print("{}: up to date ({})\n", *out, assets::kAssetsVersion);
        } else {
            for (const std::string& line : report.lines) fmt::print("{}/{}\n", *out, line);
            fmt::print("{}: generated in {:.2f} s ({})\n", *out, report.seconds, assets::kAssetsVersion);
        }
        for (const int n : *yards) fmt::print("{}\n", assets::write_yard(*out, n).string());
    });
}

RegisterCommand assets_command({"assets", "Generate the project's own assets (robot, kitchen, environments)", 90,
                                setup_assets});

}  // namespace
}  // namespace rsl::cli
