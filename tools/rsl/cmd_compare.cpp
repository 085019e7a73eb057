// `rsl compare A B`: the error of a result A against a reference B, both
// per-vertex (.rslv) or both images (.exr). Prints `relative L2: …` first.
// With --sequence, A and B are two runs' -o paths and every numbered frame
// (A.NNNN.exr against B.NNNN.exr, as --frames names them) is compared: a
// table per frame and the worst frame.
#include <fmt/core.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "tools/rsl/command.h"
#include "tools/rsl/frame_output.h"

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"
#include "src/image/error_metrics.h"
#include "src/image/image_formation.h"
#include "src/formats/vertex_colors.h"

namespace rsl::cli {
namespace {

struct CompareArgs {
    std::string a, b;
    std::string error_image;
    float error_scale = 0;
    std::string scene;
    int width = 0, height = 0;
    std::vector<std::string> receivers = kDefaultReceivers;
    bool sequence = false;
    std::string table;
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

// One frame of a sequence: its two files and their errors. `objects` is the
// objects' relative L2 for vertex files (NaN without objects), `h1` the
// relative H1 for images (NaN for vertex files).
struct FrameRow {
    std::filesystem::path a, b;
    double relative_l2 = 0, max_error = 0, relative_max = 0;
    double objects = std::nan(""), h1 = std::nan("");
};

FrameRow compare_frame(const std::filesystem::path& a_path, const std::filesystem::path& b_path, Kind kind,
                       const std::vector<std::string>& receivers) {
    FrameRow row{a_path, b_path};
    if (kind == Kind::Vertices) {
        const VertexColors a = read_vertex_colors(a_path), b = read_vertex_colors(b_path);
        check_same_vertices(a, a_path.string(), b, b_path.string());
        const VertexErrorReport report = compare_vertex_colors(a, b);
        row.relative_l2 = report.total.relative_l2();
        row.max_error = report.total.max_error;
        row.relative_max = report.total.relative_max();
        const ObjectErrorReport objects = object_errors(report, receivers);
        if (objects.object_parts > 0) row.objects = objects.objects.relative_l2();
    } else {
        const Image a = read_exr(a_path), b = read_exr(b_path);
        if (a.width != b.width || a.height != b.height)
            throw_error("{} and {} are not comparable: {}×{} vs {}×{} pixels", a_path.string(), b_path.string(),
                        a.width, a.height, b.width, b.height);
        const ImageErrorReport report = compare_images(a, b);
        row.relative_l2 = report.pixels.relative_l2();
        row.max_error = report.pixels.max_error;
        row.relative_max = report.pixels.relative_max();
        row.h1 = report.relative_h1();
    }
    return row;
}

// The numbered frames of a run's -o path: PATH.0000.ext, PATH.0001.ext, … while they exist.
std::vector<std::filesystem::path> sequence_frames(const std::string& path) {
    std::vector<std::filesystem::path> frames;
    for (int f = 0; std::filesystem::is_regular_file(numbered(path, f)); ++f) frames.push_back(numbered(path, f));
    if (frames.empty())
        throw_error("--sequence: no frame {} (give the -o path of an rsl render or rsl truth --frames run)",
                    numbered(path, 0).string());
    return frames;
}

std::string csv_number(double value) { return std::isnan(value) ? "" : fmt::format("{:.6g}", value); }

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

// The table as JSON (an array of objects) or CSV (a header row), by the file's extension.
std::string table_text(const std::filesystem::path& file, const std::vector<FrameRow>& rows) {
    if (file.extension() == ".json") {
        nlohmann::json table = nlohmann::json::array();
        for (size_t f = 0; f < rows.size(); ++f) {
            nlohmann::json row = {{"frame", f}, {"a", rows[f].a.string()}, {"b", rows[f].b.string()},
                                  {"relative_l2", rows[f].relative_l2}, {"max_error", rows[f].max_error},
                                  {"relative_max", rows[f].relative_max}};
            if (!std::isnan(rows[f].objects)) row["objects_relative_l2"] = rows[f].objects;
            if (!std::isnan(rows[f].h1)) row["relative_h1"] = rows[f].h1;
            table.push_back(row);
        }
        return table.dump(2) + "\n";
    }
    std::string csv = "frame,a,b,relative_l2,max_error,relative_max,objects_relative_l2,relative_h1\n";
    for (size_t f = 0; f < rows.size(); ++f)
        csv += fmt::format("{},{},{},{},{},{},{},{}\n", f, csv_field(rows[f].a.string()), csv_field(rows[f].b.string()),
                           csv_number(rows[f].relative_l2), csv_number(rows[f].max_error),
                           csv_number(rows[f].relative_max), csv_number(rows[f].objects), csv_number(rows[f].h1));
    return csv;
}

void compare_sequences(const CompareArgs& args, Kind kind) {
    const std::vector<std::filesystem::path> a = sequence_frames(args.a), b = sequence_frames(args.b);
    if (a.size() != b.size())
        throw_error("{} has {} frames and {} has {}: compare runs of the same --frames", args.a, a.size(), args.b,
                    b.size());
    if (!args.table.empty()) {
        const std::string extension = std::filesystem::path(args.table).extension().string();
        if (extension != ".json" && extension != ".csv")
            throw_error("--table {}: expected a .json or .csv file", args.table);
        std::vector<std::filesystem::path> inputs = a;
        inputs.insert(inputs.end(), b.begin(), b.end());
        check_outputs_apart({args.table}, inputs);
    }
    std::vector<FrameRow> rows;
    const bool images = kind == Kind::Image;
    fmt::print("{:>5}  {:>12}  {:>12}  {:>12}  {:>12}  {}\n", "frame", "relative L2", "max error", "relative max",
               images ? "relative H1" : "objects L2", "A");
    size_t worst = 0;
    for (size_t f = 0; f < a.size(); ++f) {
        rows.push_back(compare_frame(a[f], b[f], kind, args.receivers));
        const FrameRow& row = rows.back();
        fmt::print("{:>5}  {:>12.6g}  {:>12.6g}  {:>12.6g}  {:>12}  {}\n", f, row.relative_l2, row.max_error,
                   row.relative_max, csv_number(images ? row.h1 : row.objects), row.a.filename().string());
        if (row.relative_l2 > rows[worst].relative_l2) worst = f;
    }
    fmt::print("worst frame: {} ({} against {}), relative L2 {:.6g}, max error {:.6g}\n", worst, a[worst].string(),
               b[worst].string(), rows[worst].relative_l2, rows[worst].max_error);
    if (!args.table.empty()) {
        write_file_atomically(args.table, table_text(args.table, rows));
        fmt::print("table: {} ({} frames)\n", args.table, rows.size());
    }
}

RegisterCommand compare_command({"compare",
    "Error of A against the reference B (both .rslv or both .exr): relative L2, max, the objects and the worst part, per part, H1 for images",
    50, [](CLI::App& app) {
        auto args = std::make_shared<CompareArgs>();
        app.add_option("a", args->a, "Result to measure (.rslv or .exr); with --sequence, a run's -o or --vertex-out path")->required();
        app.add_option("b", args->b, "Reference, e.g. from rsl truth (same kind as A); with --sequence, the reference run's")->required();
        app.add_flag("--sequence", args->sequence,
                     "Compare two --frames runs frame by frame: A.0000.exr against B.0000.exr, and so on (or "
                     ".rslv); prints a row per frame and the worst frame");
        app.add_option("--table", args->table, "With --sequence: also write the table to this .json or .csv file");
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
            if (args->sequence) {
                if (!args->error_image.empty()) throw_error("--error-image compares one pair: leave out --sequence");
                compare_sequences(*args, ka);
                return;
            }
            if (!args->table.empty()) throw_error("--table {}: the table is of a --sequence", args->table);
            for (const std::string& path : {args->a, args->b})
                if (!std::filesystem::is_regular_file(path))
                    throw_error("{}: no such file{}", path,
                                std::filesystem::is_regular_file(numbered(path, 0))
                                    ? fmt::format(" ({} exists: add --sequence to compare a --frames run)",
                                                  numbered(path, 0).string())
                                    : "");
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
