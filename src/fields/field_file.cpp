#include "src/fields/field_file.h"

#include <cmath>
#include <cstring>

#include <Imath/half.h>
#include <nlohmann/json.hpp>

#include "src/core/atomic_file.h"
#include "src/formats/binary_io.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"
#include "src/shading/ovdf_tables.h"

namespace rsl {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr char kMagic[8] = {'R', 'S', 'L', 'F', 'I', 'E', 'L', 'D'};

json to_json(const SvdfParams& p) {
    return {{"resolution", p.resolution}, {"supersampling", p.supersampling}, {"coarse_to_fine", p.coarse_to_fine},
            {"clusters", p.clusters},     {"vectors", p.vectors},             {"refine_iterations", p.refine_iterations},
            {"mode", int(p.mode)},        {"below_horizon", int(p.below_horizon)},
            {"half_precision_tables", p.half_precision_tables}, {"seed", p.seed}};
}
json to_json(const OvdfParams& p) {
    return {{"shells", p.shells},
            {"inner_radius", p.inner_radius},
            {"outer_radius", p.outer_radius},
            {"spacing", int(p.spacing)},
            {"cube_resolution", p.cube_resolution},
            {"vdt_resolution", p.vdt_resolution},
            {"vectors", p.vectors},
            {"segments_per_side", p.segments_per_side},
            {"supersampling", p.supersampling},
            {"mode", int(p.mode)},
            {"half_precision_tables", p.half_precision_tables},
            {"seed", p.seed}};
}
// The parameter block's values, each of its type and within what the
// lookups and prepare() rely on (resolutions of at least 2: bilinear taps;
// 2 shells: shell pairs; segments that divide the cube faces). Limits of 256
// are the scene file's (docs/SCENE_FORMAT.md) and keep every count an int.
class ParamReader {
public:
    ParamReader(const json& j, const fs::path& path) : j_(j), path_(path) {}

    int integer(const char* key, int least, int most) const {
        const json& v = value(key);
        if (!v.is_number_integer() || (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(most)) ||
            v.get<int64_t>() < least || v.get<int64_t>() > most)
            fail(key, fmt::format("{} is not an integer from {} to {}", v.dump(), least, most));
        return int(v.get<int64_t>());
    }
    float positive(const char* key) const {
        const json& v = value(key);
        const double x = v.is_number() ? v.get<double>() : 0.0;
        if (!(x > 0 && x < 1e30)) fail(key, fmt::format("{} is not a positive number", v.dump()));
        return float(x);
    }
    bool flag(const char* key) const {
        const json& v = value(key);
        if (!v.is_boolean()) fail(key, fmt::format("{} is not true or false", v.dump()));
        return v.get<bool>();
    }
    uint64_t seed() const {
        const json& v = value("seed");
        if (!v.is_number_unsigned()) fail("seed", fmt::format("{} is not an unsigned integer", v.dump()));
        return v.get<uint64_t>();
    }
    [[noreturn]] void fail(const char* key, const std::string& what) const {
        throw_file_error(path_, "bad parameter block: {}: {}", key, what);
    }

private:
    const json& value(const char* key) const {
        if (!j_.is_object() || !j_.contains(key)) fail(key, "missing");
        return j_[key];
    }
    const json& j_;
    const fs::path& path_;
};

SvdfParams svdf_params_from(const json& j, const fs::path& path) {
    const ParamReader r(j, path);
    SvdfParams p;
    p.resolution = r.integer("resolution", 2, 256);
    p.supersampling = r.integer("supersampling", 1, 256);
    p.coarse_to_fine = r.flag("coarse_to_fine");
    p.clusters = r.integer("clusters", 1, 1 << 24);
    p.vectors = r.integer("vectors", 0, 1024);
    p.refine_iterations = r.integer("refine_iterations", 0, 1 << 20);
    p.mode = VdtMode(r.integer("mode", 0, 1));
    p.below_horizon = BelowHorizon(r.integer("below_horizon", 0, 2));
    p.half_precision_tables = r.flag("half_precision_tables");
    p.seed = r.seed();
    return p;
}
OvdfParams ovdf_params_from(const json& j, const fs::path& path) {
    const ParamReader r(j, path);
    OvdfParams p;
    p.shells = r.integer("shells", 2, 256);
    p.inner_radius = r.positive("inner_radius");
    p.outer_radius = r.positive("outer_radius");
    if (!(p.outer_radius > p.inner_radius)) r.fail("outer_radius", "not above inner_radius");
    p.spacing = ShellSpacing(r.integer("spacing", 0, 2));
    p.cube_resolution = r.integer("cube_resolution", 2, 256);
    p.vdt_resolution = r.integer("vdt_resolution", 2, 256);
    p.vectors = r.integer("vectors", 0, 1024);
    p.segments_per_side = r.integer("segments_per_side", 1, p.cube_resolution);
    if (p.cube_resolution % p.segments_per_side != 0) r.fail("segments_per_side", "does not divide cube_resolution");
    p.supersampling = r.integer("supersampling", 1, 256);
    p.mode = VdtMode(r.integer("mode", 0, 1));
    p.half_precision_tables = r.flag("half_precision_tables");
    p.seed = r.seed();
    return p;
}

void put_model(BinaryWriter& w, const CpcaModel& m, bool half_tables) {
    w.put(int32_t(m.dims));
    w.put(int32_t(m.vectors));
    w.put(int32_t(m.clusters));
    w.put(int32_t(m.samples()));
    w.put(uint8_t(half_tables));
    if (half_tables) {
        for (float v : m.tables) w.put(Imath::half(v).bits());
    } else {
        w.put_bytes(m.tables.data(), m.tables.size() * sizeof(float));
    }
    if (m.clusters <= 65536) {
        for (int32_t c : m.assignment) w.put(uint16_t(c));
    } else {
        w.put_bytes(m.assignment.data(), m.assignment.size() * sizeof(int32_t));
    }
    w.put_bytes(m.coefficients.data(), m.coefficients.size() * sizeof(float));
}

void write_field(const fs::path& path, FieldKind kind, uint64_t mesh, const std::string& params,
                 const Ovdf* ovdf, const CpcaModel& model, bool half_tables) {
    BinaryWriter w;
    w.put_bytes(kMagic, sizeof(kMagic));
    w.put(kFieldFormatVersion);
    w.put(uint32_t(kind));
    w.put(mesh);
    w.put(params_hash(params));
    w.put_string(params);
    if (ovdf) {
        w.put(ovdf->center);
        w.put(ovdf->radius);
    }
    put_model(w, model, half_tables);
    if (ovdf) {
        RSL_CHECK_EQ(ovdf->surface_distance.size(), ovdf->params.sample_count());
        w.put_bytes(ovdf->surface_distance.data(), ovdf->surface_distance.size() * sizeof(float));
        RSL_CHECK_EQ(ovdf->occluded_area.size(), ovdf->params.sample_count());
        w.put_bytes(ovdf->occluded_area.data(), ovdf->occluded_area.size() * sizeof(float));
        RSL_CHECK_EQ(ovdf->radial_span.size(), size_t(2 * shading::kCubeFaces) * ovdf->span_resolution * ovdf->span_resolution);
        w.put(int32_t(ovdf->span_resolution));
        w.put_bytes(ovdf->radial_span.data(), ovdf->radial_span.size() * sizeof(float));
    }
    write_file_atomically(path, w.finish_with_checksum());
}

// Checks magic, size, checksum and version; returns the header and leaves the
// reader just after the parameters.
FieldHeader parse_header(const fs::path& path, const std::string& bytes, BinaryReader& r) {
    FieldHeader h;
    h.file_bytes = bytes.size();
    if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
        throw_file_error(path, "not an rsl field file (bad magic)");
    constexpr size_t kMinimum = 8 + 4 + 4 + 8 + 8 + 4 + 8;
    if (bytes.size() < kMinimum) throw_file_error(path, "truncated field file ({} bytes)", bytes.size());
    h.checksum = stored_checksum(bytes);
    if (!has_valid_checksum(bytes))
        throw_file_error(path, "checksum mismatch: the field file is corrupt or truncated; re-run `rsl bake`");
    char magic[8];
    r.get_bytes(magic, 8);
    h.version = r.get<uint32_t>();
    if (h.version != kFieldFormatVersion)
        throw_file_error(path, "stale field file: format version {}, this rsl reads version {}; re-run `rsl bake`",
                         h.version, kFieldFormatVersion);
    const uint32_t kind = r.get<uint32_t>();
    if (kind != uint32_t(FieldKind::Svdf) && kind != uint32_t(FieldKind::Ovdf))
        throw_file_error(path, "unknown field kind {}", kind);
    h.kind = FieldKind(kind);
    h.mesh_hash = r.get<uint64_t>();
    h.params_hash = r.get<uint64_t>();
    h.params = r.get_string("parameters");
    if (params_hash(h.params) != h.params_hash) throw_file_error(path, "parameter block does not match its hash");
    return h;
}

void check_expectation(const fs::path& path, const FieldHeader& h, FieldKind kind, const FieldExpectation& e) {
    if (h.kind != kind)
        throw_file_error(path, "holds an {} where an {} was expected", h.kind == FieldKind::Svdf ? "SVDF" : "OVDF",
                         kind == FieldKind::Svdf ? "SVDF" : "OVDF");
    if (e.mesh_hash && *e.mesh_hash != h.mesh_hash)
        throw_file_error(path, "stale field file: baked for a different mesh (hash {:016x}, expected {:016x}); "
                               "re-run `rsl bake`",
                         h.mesh_hash, *e.mesh_hash);
    if (e.params && params_hash(*e.params) != h.params_hash)
        throw_file_error(path, "stale field file: baked with parameters {} but {} are expected; re-run `rsl bake`",
                         h.params, *e.params);
}

void check_all_finite(const fs::path& path, const std::vector<float>& values, const char* what) {
    for (size_t k = 0; k < values.size(); ++k)
        if (!std::isfinite(values[k])) throw_file_error(path, "non-finite {} {} at index {}", what, values[k], k);
}

// Finite numbers can still overflow: μ + Σ w·b with w near 1e38 is infinite.
// No lookup (a convex blend of texels and of samples) can exceed, per
// cluster, max|μ| + Σ_m max|b_m|·max|w_m|; a baked field's bound is a few
// thousand plane units (|distance| ≤ 2√2, unit basis vectors).
void check_reconstruction_bound(const fs::path& path, const CpcaModel& m) {
    constexpr double kLimit = 1e6;
    const int rows = m.vectors + 1;
    std::vector<double> table_max(size_t(m.clusters) * rows, 0.0), weight_max(size_t(m.clusters) * rows, 0.0);
    for (int c = 0; c < m.clusters; ++c)
        for (int t = 0; t < m.dims; ++t) {
            const float* row = m.row(c, t);
            for (int k = 0; k < rows; ++k)
                table_max[size_t(c) * rows + k] = std::max(table_max[size_t(c) * rows + k], double(std::abs(row[k])));
        }
    for (int s = 0; s < m.samples(); ++s) {
        const float* w = m.coefficients_of(s);
        double* out = &weight_max[size_t(m.assignment[s]) * rows];
        out[0] = 1.0;  // the mean's weight
        for (int k = 0; k < m.vectors; ++k) out[k + 1] = std::max(out[k + 1], double(std::abs(w[k])));
    }
    for (int c = 0; c < m.clusters; ++c) {
        double bound = 0;
        for (int k = 0; k < rows; ++k) bound += table_max[size_t(c) * rows + k] * weight_max[size_t(c) * rows + k];
        if (!(bound <= kLimit))
            throw_file_error(path, "implausible field: cluster {} reconstructs distances up to {:g} (a baked field "
                                   "stays within {:g})",
                             c, bound, kLimit);
    }
}

CpcaModel get_model(const fs::path& path, BinaryReader& r, FieldHeader& h) {
    CpcaModel m;
    m.dims = h.dims = r.get<int32_t>();
    m.vectors = h.vectors = r.get<int32_t>();
    m.clusters = h.clusters = r.get<int32_t>();
    h.samples = r.get<int32_t>();
    h.half_tables = r.get<uint8_t>() != 0;
    if (m.dims <= 0 || m.vectors < 0 || m.clusters <= 0 || h.samples <= 0 || m.dims > (1 << 20) ||
        m.vectors > 1024 || size_t(m.clusters) > size_t(h.samples))
        throw_file_error(path, "implausible model sizes (dims {}, vectors {}, clusters {}, samples {})", m.dims,
                         m.vectors, m.clusters, h.samples);
    // Sizes must fit the bytes left before anything is allocated (a crafted
    // header could otherwise ask for terabytes). Bounded above: no overflow.
    const uint64_t tables = uint64_t(m.clusters) * uint64_t(m.dims) * uint64_t(m.vectors + 1);
    const uint64_t payload = tables * (h.half_tables ? 2 : 4) + uint64_t(h.samples) * (m.clusters <= 65536 ? 2 : 4) +
                             uint64_t(h.samples) * uint64_t(m.vectors) * 4;
    if (payload > r.remaining())
        throw_file_error(path, "truncated or corrupt: the model needs {} bytes, the file holds {}", payload,
                         r.remaining());
    m.tables.resize(tables);
    if (h.half_tables) {
        for (float& v : m.tables) {
            Imath::half x;
            x.setBits(r.get<uint16_t>());
            v = float(x);
        }
    } else {
        r.get_bytes(m.tables.data(), m.tables.size() * sizeof(float));
    }
    m.assignment.resize(h.samples);
    if (m.clusters <= 65536) {
        for (int32_t& c : m.assignment) c = r.get<uint16_t>();
    } else {
        r.get_bytes(m.assignment.data(), m.assignment.size() * sizeof(int32_t));
    }
    for (int32_t c : m.assignment)
        if (c < 0 || c >= m.clusters) throw_file_error(path, "cluster index {} out of range", c);
    m.coefficients.resize(size_t(h.samples) * m.vectors);
    r.get_bytes(m.coefficients.data(), m.coefficients.size() * sizeof(float));
    // A checksum proves the bytes are the ones written, not that a writer
    // wrote numbers: NaN or infinity would shade every vertex that uses them.
    check_all_finite(path, m.tables, "table value");
    check_all_finite(path, m.coefficients, "PCA coefficient");
    check_reconstruction_bound(path, m);
    return m;
}

// The magic number first, then the size, before the rest is read: a link to a
// huge or endless file in the cache costs eight bytes.
std::string read_field_bytes(const fs::path& path) {
    return read_bounded_file(path, kMaxFieldFileBytes, "a field file", std::string_view(kMagic, sizeof(kMagic)),
                             "not an rsl field file (bad magic)");
}

// The payload ends where the trailing checksum begins.
size_t payload_end(const std::string& bytes) { return bytes.size() >= 8 ? bytes.size() - 8 : 0; }

// The file's parameters after checking it is the expected kind, mesh and
// parameters (stale files are refused here).
template <typename Params>
Params expected_params(const fs::path& path, const FieldHeader& h, FieldKind kind, const FieldExpectation& expect,
                       Params (*from_json)(const json&, const fs::path&)) {
    check_expectation(path, h, kind, expect);
    try {
        return from_json(json::parse(h.params), path);
    } catch (const json::exception& e) {
        throw_file_error(path, "bad parameter block: {}", e.what());
    }
}

void check_fully_read(const fs::path& path, const BinaryReader& r) {
    if (r.remaining() != 0) throw_file_error(path, "trailing bytes after the payload");
}

}  // namespace

uint64_t mesh_hash(const TriangleMesh& mesh) {
    uint64_t h = fnv1a64(mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
    h = fnv1a64(mesh.normals.data(), mesh.normals.size() * sizeof(Vec3), h);
    h = fnv1a64(mesh.tangents.data(), mesh.tangents.size() * sizeof(Vec4), h);
    return fnv1a64(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t), h);
}

std::string params_json(const SvdfParams& params) { return to_json(params).dump(); }
std::string params_json(const OvdfParams& params) { return to_json(params).dump(); }

void write_svdf(const fs::path& path, const Svdf& svdf, uint64_t mesh) {
    write_field(path, FieldKind::Svdf, mesh, params_json(svdf.params), nullptr, svdf.model,
                svdf.params.half_precision_tables);
}

void write_ovdf(const fs::path& path, const Ovdf& ovdf, uint64_t mesh) {
    write_field(path, FieldKind::Ovdf, mesh, params_json(ovdf.params), &ovdf, ovdf.model,
                ovdf.params.half_precision_tables);
}

namespace {

// Opens the field file at `path`, checks its header and hands `read` the
// reader (after the header) and the header.
template <class Read>
auto read_field(const fs::path& path, Read read) {
    const std::string bytes = read_field_bytes(path);
    BinaryReader r(path, bytes, payload_end(bytes));
    FieldHeader h = parse_header(path, bytes, r);
    return read(r, h);
}

// An OVDF's payload after its header: the bounding sphere, the model, the
// per-sample tables and the radial spans, each checked.
Ovdf read_ovdf_payload(const fs::path& path, const FieldExpectation& expect, BinaryReader& r, FieldHeader& h) {
    Ovdf ovdf;
    ovdf.params = expected_params(path, h, FieldKind::Ovdf, expect, ovdf_params_from);
    ovdf.center = r.get<Vec3>();
    ovdf.radius = r.get<float>();
    if (!std::isfinite(ovdf.center.x + ovdf.center.y + ovdf.center.z) || !(ovdf.radius > 0 && ovdf.radius < 1e30f))
        throw_file_error(path, "implausible OVDF bounding sphere (center {}, {}, {}, radius {})", ovdf.center.x,
                         ovdf.center.y, ovdf.center.z, ovdf.radius);
    ovdf.model = get_model(path, r, h);
    if (h.dims != ovdf.params.vdt_resolution * ovdf.params.vdt_resolution ||
        size_t(h.samples) != ovdf.params.sample_count() || h.clusters != ovdf.params.segment_count())
        throw_file_error(path, "model sizes do not match the OVDF parameters");
    ovdf.surface_distance.resize(ovdf.params.sample_count());
    r.get_bytes(ovdf.surface_distance.data(), ovdf.surface_distance.size() * sizeof(float), "surface distances");
    check_all_finite(path, ovdf.surface_distance, "surface distance");
    ovdf.occluded_area.resize(ovdf.params.sample_count());
    r.get_bytes(ovdf.occluded_area.data(), ovdf.occluded_area.size() * sizeof(float), "occluded areas");
    check_all_finite(path, ovdf.occluded_area, "occluded area");
    for (const float area : ovdf.occluded_area)  // a table's whole plane at the smallest zoom (1/√2) is 8
        if (!(area >= 0.0f && area <= 8.0f + 1e-3f))
            throw_file_error(path, "implausible occluded area {} (0 to 8 plane units²)", area);
    ovdf.span_resolution = r.get<int32_t>();
    if (ovdf.span_resolution != 0 && (ovdf.span_resolution < 2 || ovdf.span_resolution > kMostSpanResolution))
        throw_file_error(path, "implausible radial span resolution {} (0, or 2 to {})", ovdf.span_resolution,
                         kMostSpanResolution);
    ovdf.radial_span.resize(size_t(2 * shading::kCubeFaces) * ovdf.span_resolution * ovdf.span_resolution);
    r.get_bytes(ovdf.radial_span.data(), ovdf.radial_span.size() * sizeof(float), "radial spans");
    check_all_finite(path, ovdf.radial_span, "radial span");
    check_fully_read(path, r);
    ovdf.prepare();
    return ovdf;
}

}  // namespace

FieldHeader read_field_header(const fs::path& path) {
    return read_field(path, [&](BinaryReader& r, FieldHeader& h) {
        if (h.kind == FieldKind::Ovdf) {
            r.get<Vec3>();
            r.get<float>();
        }
        get_model(path, r, h);
        return h;
    });
}

Svdf read_svdf(const fs::path& path, const FieldExpectation& expect) {
    return read_field(path, [&](BinaryReader& r, FieldHeader& h) {
        Svdf svdf;
        svdf.params = expected_params(path, h, FieldKind::Svdf, expect, svdf_params_from);
        svdf.model = get_model(path, r, h);
        if (h.dims != svdf.params.resolution * svdf.params.resolution)
            throw_file_error(path, "table size {} does not match resolution {}", h.dims, svdf.params.resolution);
        check_fully_read(path, r);
        return svdf;
    });
}

Ovdf read_ovdf(const fs::path& path, const FieldExpectation& expect) {
    return read_field(path, [&](BinaryReader& r, FieldHeader& h) { return read_ovdf_payload(path, expect, r, h); });
}

}  // namespace rsl
