// `rsl info FILE.rslf`: a field file's header, sizes, and checksum check.
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "src/fields/field_file.h"
#include "tools/rsl/info.h"
#include "src/shading/ovdf_tables.h"

namespace rsl::cli {
namespace {

void print_field_file(const std::filesystem::path& path) {
    const FieldHeader h = read_field_header(path);  // throws on a bad magic, size, checksum or version
    // ... and the whole field as the renderer reads it (parameters, bounding
    // sphere, values), so that "OK" below means it loads.
    int span_resolution = 0;
    float largest_area = 0.0f;  // the samples' largest occluded area (shading::ovdf_area_bound)
    if (h.kind == FieldKind::Svdf) {
        read_svdf(path);
    } else {
        const Ovdf ovdf = read_ovdf(path);
        span_resolution = ovdf.span_resolution;
        for (const float area : ovdf.occluded_area) largest_area = std::max(largest_area, area);
    }
    const size_t raw = size_t(h.samples) * h.dims * sizeof(float);
    fmt::print("{}: rsl field file, format version {}, {}\n", path.string(), h.version,
               h.kind == FieldKind::Svdf ? "SVDF (self-visibility, per vertex)" : "OVDF (occluder, shells of samples)");
    fmt::print("  mesh hash      {:016x}\n", h.mesh_hash);
    fmt::print("  parameters     {}\n", h.params);
    fmt::print("  samples        {} ({} each: VDT {}x{})\n", h.samples, h.kind == FieldKind::Svdf ? "vertex" : "point",
               int(std::lround(std::sqrt(h.dims))), int(std::lround(std::sqrt(h.dims))));
    fmt::print("  compression    {} {} x {} vectors, tables in {}\n", h.clusters,
               h.kind == FieldKind::Svdf ? "clusters" : "segments", h.vectors, h.half_tables ? "half" : "float");
    if (h.kind == FieldKind::Ovdf) {
        fmt::print("  radial spans   {}x{} lines per cube face (the receivers' inside test, src/fields/ovdf_spans.h)\n",
                   span_resolution, span_resolution);
        fmt::print("  occluded area  per sample, up to {:.3f} plane units² (bounds the shadowed share of large squares)\n",
                   largest_area);
    }
    fmt::print("  size           {:.2f} MB on disk, {:.2f} MB as raw float (1:{:.1f})\n", h.file_bytes / 1e6,
               raw / 1e6, double(raw) / double(h.file_bytes));
    fmt::print("  checksum       {:016x} (FNV-1a 64) OK, contents OK\n", h.checksum);
}

RegisterInfoHandler field_info({"field", [](const auto& p) { return lowercase_extension(p) == ".rslf"; },
                                print_field_file});

}  // namespace
}  // namespace rsl::cli
