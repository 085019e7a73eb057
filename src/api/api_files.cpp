// The free functions of the public API (include/rsl/rsl.h): what `rsl fit`,
// `rsl compare` and `rsl --version` run, and the program's files.
#include <cmath>
#include <chrono>

#include <fmt/format.h>

#include "src/formats/environment_file.h"
#include "src/formats/image_file.h"
#include "src/lightfit/scene_lights.h"
#include "src/lightfit/reconstruct.h"
#include "src/api/api_convert.h"
#include "src/backend/make_renderer.h"
#include "src/core/envmap.h"
#include "src/image/error_metrics.h"
#include "src/render/part_fields.h"
#include "src/render/cpu_renderer.h"
#include "src/core/atomic_file.h"
#include "src/core/memory_limit.h"
#include "src/version/build_info.h"

namespace rsl::api {

SetupReport bake_fields(const Scene& scene, const std::string& field_cache, const Progress& progress) {
    const rsl::Scene& s = scene.internal();
    if (s.source.empty() && field_cache.empty())
        throw_error("bake_fields: scene '{}' has no file to keep its fields beside: give a field_cache folder", s.name);
    FieldBakeOptions options;
    options.cache_directory = field_cache;
    options.progress = throttled(progress);
    const auto start = std::chrono::steady_clock::now();
    FieldLoadReport report;
    load_part_fields(s, options, &report);
    SetupReport setup;
    setup.fields_loaded = report.loaded, setup.fields_baked = report.baked;
    setup.bake_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return setup;
}

EnvironmentFit fit_environment(const std::string& file, int lights, int resolution, bool cross_face) {
    // The checks and defaults of `rsl fit`.
    if (resolution < 1 || resolution > kMaxCubeResolution)
        throw_error("resolution {}: expected 1..{} texels per cube-face edge", resolution, kMaxCubeResolution);
    if (lights < 1) throw_error("lights {}: expected at least 1", lights);
    if (!cross_face && lights < 6)
        throw_error("lights {} without cross_face: regions never cross a cube face, so at least 6", lights);
    const CubeMap map = load_environment(file, resolution);
    const RslSet set = fit_environment_lights(map, lights, cross_face);
    EnvironmentFit fit;
    for (const RotatableSquareLight& l : set.lights)
        fit.lights.push_back({to_float3(l.center), l.half_diagonal, to_float3(l.radiance)});
    fit.resolution = map.resolution();
    fit.relative_l2 = lightfit::relative_l2_error(map, lightfit::reconstruct(set, map.resolution()));
    fit.map_energy = to_float3(Vec3(map.energy()));
    fit.light_energy = to_float3(Vec3(set.total_energy()));
    return fit;
}

namespace {
// NaN compares false against everything, so a NaN value would read as no error at all.
void check_finite_values(const std::vector<float>& values, const std::string& what, int per_item, const char* item) {
    for (size_t k = 0; k < values.size(); ++k)
        if (!std::isfinite(values[k]))
            throw_error("{}: {} {} holds {}: a comparison needs finite values", what, item, k / per_item, values[k]);
}
}  // namespace

VertexError compare(const VertexColors& result, const VertexColors& reference,
                    const std::vector<std::string>& receivers) {
    check_finite_values(result.rgb, "compare result", 3, "vertex");
    check_finite_values(reference.rgb, "compare reference", 3, "vertex");
    const ::rsl::VertexColors a = to_internal(result, "compare result"), b = to_internal(reference, "compare reference");
    check_same_vertices(a, "result", b, "reference");
    const VertexErrorReport report = compare_vertex_colors(a, b);
    VertexError error;
    error.relative_l2 = report.total.relative_l2();
    error.max_error = report.total.max_error;
    error.relative_max = report.total.relative_max();
    error.count = report.total.count;
    error.part_names = report.part_names;
    for (const ErrorStats& part : report.parts) error.part_relative_l2.push_back(part.relative_l2());
    const ObjectErrorReport objects = object_errors(report, receivers);
    error.objects_relative_l2 = objects.objects.relative_l2();
    error.object_parts = objects.object_parts;
    error.worst_part = objects.worst_part;
    error.worst_relative_l2 = objects.worst;
    return error;
}

ImageError compare(const Image& result, const Image& reference) {
    check_finite_values(result.rgba, "compare result", 4, "pixel");
    check_finite_values(reference.rgba, "compare reference", 4, "pixel");
    const ::rsl::Image a = to_internal(result, "compare result"), b = to_internal(reference, "compare reference");
    if (a.width != b.width || a.height != b.height)
        throw_error("result and reference are not comparable: {}×{} vs {}×{} pixels", a.width, a.height, b.width,
                    b.height);
    const ImageErrorReport report = compare_images(a, b);
    return {report.pixels.relative_l2(), report.relative_h1(), report.pixels.max_error, report.covered, report.total};
}

namespace {

// check_outputs_apart (src/core/atomic_file.h) with the API's strings.
void check_apart(const std::vector<std::filesystem::path>& outputs, const std::vector<std::string>& inputs) {
    check_outputs_apart(outputs, std::vector<std::filesystem::path>(inputs.begin(), inputs.end()));
}

}  // namespace

void write_image(const std::string& exr_path, const Image& image, float exposure,
                 const std::vector<std::string>& inputs) {
    if (std::filesystem::path(exr_path).extension() != ".exr")
        throw_error("{}: expected an .exr path (a .png preview is written beside it)", exr_path);
    check_apart({exr_path, std::filesystem::path(exr_path).replace_extension(".png")}, inputs);
    write_exr_and_png(exr_path, to_internal(image, exr_path), ToneMap{exposure, exposure == 0.0f});
}

Image read_image(const std::string& exr_path) { return to_api(read_exr(exr_path)); }

void write_vertex_colors(const std::string& rslv_path, const VertexColors& colors,
                         const std::vector<std::string>& inputs) {
    check_apart({rslv_path}, inputs);
    ::rsl::write_vertex_colors(rslv_path, to_internal(colors, rslv_path));
}

VertexColors read_vertex_colors(const std::string& rslv_path) { return to_api(::rsl::read_vertex_colors(rslv_path)); }

uint64_t memory_limit() { return ::rsl::memory_limit(); }
void set_memory_limit(uint64_t bytes) { ::rsl::set_memory_limit(bytes); }
void set_memory_limit(const std::string& size) {
    ::rsl::set_memory_limit(::rsl::parse_memory_size(size, "set_memory_limit"));
}

BuildInfo build_info() {
    const ::rsl::BuildInfo info = ::rsl::build_info();
    return {info.version, info.commit, info.build_type, info.embree, info.openexr, available_backends()};
}

}  // namespace rsl::api
