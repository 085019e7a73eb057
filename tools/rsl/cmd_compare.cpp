// `rsl compare A B`: the error of a result A against a reference B, both
// per-vertex (.rslv) or both images (.exr). Prints `relative L2: …` first.
#include <fmt/core.h>
#include <fmt/format.h>

#include "tools/rsl/command.h"
#include <optional>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/core/image.h"
#include "src/core/scene.h"
#include "src/frame/error_metrics.h"
#include "src/frame/image_formation.h"
#include "src/frame/vertex_colors.h"

namespace rsl::cli {
namespace {

struct CompareArgs {
    std::string a, b;
    std::string error_image;
    float error_scale = 0;
    std::string scene;
    int width = 0, height = 0;
    std::vector<std::string> receivers = kDefaultReceivers;
};

enum class Kind { Vertices, Image };

Kind kind_of(const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".rslv") return Kind::Vertices;
    if (ext == ".exr") return Kind::Image;
    throw_file_error(path, "expected a per-vertex .rslv file or an .exr image");
}

// The per-vertex error |a − b| in false colour, formed into an image of `scene`.
void write_vertex_error_image(const CompareArgs& args, const Scene& scene, const VertexColors& a,
                              const VertexColors& b, float scale) {
    VertexColors error = b;
    for (size_t p = 0; p < error.parts.size(); ++p)
        for (size_t v = 0; v < error.parts[p].size(); ++v)
            error.parts[p][v] = false_color(glm::length(a.parts[p][v] - b.parts[p][v]) / scale);
    const PosedScene posed(scene, b.time);
    const PinholeCamera camera = PinholeCamera::at_time(scene.camera, b.time, args.width > 0 ? args.width : scene.camera.width,
                                                        args.height > 0 ? args.height : scene.camera.height);
    write_png(args.error_image, form_image(posed, camera, error));
}

void compare_vertices(const CompareArgs& args, const Scene* scene) {
    const VertexColors a = read_vertex_colors(args.a), b = read_vertex_colors(args.b);
    check_same_vertices(a, args.a, b, args.b);
    const VertexErrorReport report = compare_vertex_colors(a, b);
    fmt::print("relative L2: {:.6g} (‖A − B‖₂ / ‖B‖₂, RGB over {} vertices; A = {} [{}], B = {} [{}])\n",
               report.total.relative_l2(), report.total.count, args.a, a.producer, args.b, b.producer);
    fmt::print("max error: {:.6g} (RGB distance; {:.6g} of the largest reference value {:.6g})\n",
               report.total.max_error, report.total.relative_max(), report.total.max_reference);
    const ObjectErrorReport objects = object_errors(report, args.receivers);
    if (objects.object_parts > 0)
        fmt::print("objects: relative L2 {:.6g} over {} vertices of {} parts (all but the receivers {}); "
                   "worst part {}: {:.6g}\n",
                   objects.objects.relative_l2(), objects.objects.count, objects.object_parts,
                   fmt::join(args.receivers, ", "), objects.worst_part, objects.worst);
    for (size_t p = 0; p < report.parts.size(); ++p)
        fmt::print("part {}: relative L2 {:.6g}, max error {:.6g}, {} vertices\n", report.part_names[p],
                   report.parts[p].relative_l2(), report.parts[p].max_error, report.parts[p].count);
    if (!args.error_image.empty()) {
        if (!scene)
            throw_error("--error-image with vertex files needs --scene SCENE (the geometry to draw the error on)");
        const float scale = args.error_scale > 0 ? args.error_scale : float(std::max(report.total.max_error, 1e-30));
        write_vertex_error_image(args, *scene, a, b, scale);
        fmt::print("error image: {} (false colour, full scale = {:.6g})\n", args.error_image, scale);
    }
}

void compare_image_files(const CompareArgs& args) {
    const Image a = read_exr(args.a), b = read_exr(args.b);
    if (a.width != b.width || a.height != b.height)
        throw_error("{} and {} are not comparable: {}×{} vs {}×{} pixels", args.a, args.b, a.width, a.height,
                    b.width, b.height);
    const ImageErrorReport report = compare_images(a, b);
    fmt::print("relative L2: {:.6g} (‖A − B‖₂ / ‖B‖₂, RGB over {} covered pixels of {})\n",
               report.pixels.relative_l2(), report.covered, report.total);
    fmt::print("max error: {:.6g} (RGB distance; {:.6g} of the largest reference value {:.6g})\n",
               report.pixels.max_error, report.pixels.relative_max(), report.pixels.max_reference);
    fmt::print("relative H1: {:.6g} (L2 of the image-gradient difference / gradient norm of B)\n",
               report.relative_h1());
    if (!args.error_image.empty()) {
        write_png(args.error_image, error_image(a, b, args.error_scale));
        fmt::print("error image: {} (false colour, full scale = {:.6g})\n", args.error_image,
                   args.error_scale > 0 ? double(args.error_scale) : report.pixels.max_error);
    }
}

RegisterCommand compare_command({"compare",
    "Error of A against the reference B (both .rslv or both .exr): relative L2, max, the objects and the worst part, per part, H1 for images",
    50, [](CLI::App& app) {
        auto args = std::make_shared<CompareArgs>();
        app.add_option("a", args->a, "Result to measure (.rslv or .exr)")->required()->check(CLI::ExistingFile);
        app.add_option("b", args->b, "Reference, e.g. from rsl truth (same kind as A)")->required()->check(CLI::ExistingFile);
        app.add_option("--error-image", args->error_image, "Write |A − B| in false colour to this PNG");
        app.add_option("--error-scale", args->error_scale, "Error shown at full scale (default: the largest error)");
        app.add_option("--scene", args->scene, "Scene to draw a per-vertex error image on (vertex files)");
        app.add_option("--width", args->width, "Error image width for vertex files (default: the camera's)");
        app.add_option("--height", args->height, "Error image height for vertex files (default: the camera's)");
        app.add_option("--receivers", args->receivers,
                       "Parts left out of the objects' error, the static receivers (default: ground, floor, plane; a name matches in any case and with an exporter's copy number, e.g. Plane.001)")
            ->delimiter(',');
        app.callback([args] {
            const Kind ka = kind_of(args->a), kb = kind_of(args->b);
            if (ka != kb) throw_error("{} and {} are of different kinds: compare .rslv with .rslv, .exr with .exr", args->a, args->b);
            // The scene is read only to draw a vertex error image on.
            std::optional<Scene> scene;
            if (ka == Kind::Vertices && !args->error_image.empty() && !args->scene.empty()) scene = load_scene(args->scene);
            std::vector<std::filesystem::path> inputs = {args->a, args->b};
            if (scene) inputs.insert(inputs.end(), scene->input_files.begin(), scene->input_files.end());
            check_outputs_apart({args->error_image}, inputs);
            if (ka == Kind::Vertices) compare_vertices(*args, scene ? &*scene : nullptr);
            else compare_image_files(*args);
        });
    }});

}  // namespace
}  // namespace rsl::cli
