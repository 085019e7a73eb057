#include "tools/assets/generate_all.h"

#include <chrono>
#include <mutex>
#include <string_view>

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include "tools/assets/environments.h"
#include "tools/assets/kitchen.h"
#include "tools/assets/orb.h"
#include "tools/assets/pbr_scene.h"
#include "tools/assets/robot.h"
#include "tools/assets/skinned_tube.h"
#include "tools/assets/walker.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"

namespace rsl::assets {
namespace fs = std::filesystem;

std::vector<std::string> generated_file_names() {
    return {"robot.glb",   "ground.obj",  "orb.obj",      "kitchen.glb",  "sunsky.exr",  "sunsky.png",
            "studio.exr",  "studio.png",  "overcast.exr", "overcast.png", "pbr.glb",     "teapot.obj",  "tube.glb",
            "walker.glb"};
}

namespace {

bool up_to_date(const fs::path& dir) {
    const fs::path stamp = dir / kStampName;
    if (!fs::exists(stamp)) return false;
    std::string contents = read_file(stamp);
    while (!contents.empty() && (contents.back() == '\n' || contents.back() == '\r')) contents.pop_back();
    if (contents != kAssetsVersion) return false;
    for (const std::string& name : generated_file_names())
        if (!fs::exists(dir / name)) return false;
    return true;
}

std::string model_summary(const GeneratedModel& model) {
    std::string parts;
    for (const Part& part : model.scene.parts)
        parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", part.name, part.mesh.vertex_count());
    return fmt::format("{} parts, {} vertices ({}), {:g} s loop", model.scene.parts.size(), model.vertex_count(), parts,
                       model.loop_seconds);
}

void write_environment(const fs::path& dir, std::string_view name, const Image& image, float exposure) {
    write_exr(dir / fmt::format("{}.exr", name), image, ExrWriteOptions{false, EnvmapKind::LatLong});
    write_png(dir / fmt::format("{}.png", name), image, ToneMap{exposure, false});
}

}  // namespace

GenerateReport generate_assets(const fs::path& dir, bool force) {
    const auto start = std::chrono::steady_clock::now();
    GenerateReport report;
    const fs::path stamp = dir / kStampName;
    if (!force && up_to_date(dir)) {
        // Refresh the stamp's time so the build sees the step as done.
        std::error_code ec;
        fs::last_write_time(stamp, fs::file_time_type::clock::now(), ec);
        return report;
    }
    report.regenerated = true;
    std::error_code ec;
    fs::remove(stamp, ec);  // a failure below must leave the folder marked stale

    std::mutex lines_mutex;
    const auto note = [&](std::string line) {
        std::lock_guard lock(lines_mutex);
        report.lines.push_back(std::move(line));
    };
    tbb::parallel_invoke(
        [&] {
            const GeneratedModel robot = make_robot();
            write_glb(dir / "robot.glb", robot);
            note(fmt::format("robot.glb: {}", model_summary(robot)));
            const TriangleMesh ground = make_ground();
            write_obj(dir / "ground.obj", ground);
            note(fmt::format("ground.obj: 8 m x 8 m sheet, {} vertices, {} triangles", ground.vertex_count(),
                             ground.triangle_count()));
            const TriangleMesh orb = make_orb();
            write_obj(dir / "orb.obj", orb);
            note(fmt::format("orb.obj: sphere in a tilted ring (the materials and compare demos), {} vertices, {} "
                             "triangles", orb.vertex_count(), orb.triangle_count()));
        },
        [&] {
            const GeneratedModel kitchen = make_kitchen();
            write_glb(dir / "kitchen.glb", kitchen);
            note(fmt::format("kitchen.glb: {}", model_summary(kitchen)));
            const GeneratedModel pbr = make_pbr_showcase();
            write_glb(dir / "pbr.glb", pbr);
            note(fmt::format("pbr.glb: {}; glTF metallic-roughness materials, a 64x64 tile texture", model_summary(pbr)));
            const GeneratedModel tube = make_bending_tube(demo_tube_options());
            write_glb(dir / "tube.glb", tube);
            note(fmt::format("tube.glb: a skinned tube of {} joints bending {:g} deg in a {:g} s loop, {} vertices",
                             tube.skins[0].joint_nodes.size(), demo_tube_options().bend_degrees, tube.loop_seconds,
                             tube.skins[0].mesh.vertex_count()));
            const GeneratedModel walker = make_walker();
            write_glb(dir / "walker.glb", walker);
            note(fmt::format("walker.glb: a skinned figure of {} joints walking a circle in a {:g} s loop, {} vertices, "
                             "base colour and metallic-roughness textures",
                             walker.skins[0].joint_nodes.size(), walker.loop_seconds, walker.skins[0].mesh.vertex_count()));
            const TriangleMesh teapot = make_teapot();
            write_obj(dir / "teapot.obj", teapot);
            note(fmt::format("teapot.obj: the kitchen's teapot (instanced and animated scenes), {} vertices, {} triangles",
                             teapot.vertex_count(), teapot.triangle_count()));
        },
        [&] {
            write_environment(dir, "sunsky", make_sunsky(), 0.0f);
            note(fmt::format("sunsky.exr/.png: {}x{} lat-long, 0.5 deg sun with 75% of the energy",
                             kEnvironmentWidth, kEnvironmentHeight));
        },
        [&] {
            write_environment(dir, "studio", make_studio(), -1.0f);
            note(fmt::format("studio.exr/.png: {}x{} lat-long, three softboxes", kEnvironmentWidth, kEnvironmentHeight));
        },
        [&] {
            write_environment(dir, "overcast", make_overcast(), -0.5f);
            note(fmt::format("overcast.exr/.png: {}x{} lat-long, CIE overcast sky", kEnvironmentWidth,
                             kEnvironmentHeight));
        });
    std::sort(report.lines.begin(), report.lines.end());
    write_file_atomically(stamp, std::string(kAssetsVersion) + "\n");
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace rsl::assets
