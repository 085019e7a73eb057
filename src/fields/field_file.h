#pragma once
// Field files (.rslf): one compressed SVDF or OVDF of one part.
//
// Layout (little-endian):
//   "RSLFIELD"                     8 bytes, magic
//   u32 format version             kFieldFormatVersion
//   u32 kind                       1 = SVDF, 2 = OVDF
//   u64 mesh hash                  mesh_hash() of the part's mesh
//   u64 parameter hash             FNV-1a 64 of the parameter JSON below
//   u32 n, n bytes                 parameters as JSON (human-readable, `rsl info`)
//   OVDF only: f32 center xyz, f32 radius
//   model: i32 dims, vectors, clusters, samples; u8 half tables;
//          tables (half or float), assignment (u16 when clusters ≤ 65536, else
//          i32), coefficients (f32)
//   OVDF only: f32 surface distance per sample; f32 occluded area per
//          sample (plane units²); i32 span resolution n (0:
//          none), f32 (enter, exit) per radial line, 6·n² lines
//   u64 FNV-1a 64 checksum of every byte before it
// Readers refuse, naming the file: foreign files (magic), truncated or
// corrupt ones (size, checksum), stale ones (version, kind, mesh hash or
// parameters differing from what the caller expects).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "src/fields/ovdf.h"
#include "src/fields/svdf.h"
#include "src/core/checksum.h"
#include "src/core/mesh.h"
#include "src/shading/ovdf_tables.h"

namespace rsl {

// Bumped whenever what a table means changes, not only the layout: version 2
// stores OVDF tables zoomed to each shell's bounding cone (src/fields/ovdf.h), so
// version-1 OVDF files, which would read back as valid, are rebaked. Version
// 3: OVDF samples inside the part trace from the surface outside them.
// Version 4: SVDF vertices on the part's own surface elsewhere (a box
// standing on another box of one mesh) count as outside it
// (RayScene's origins_outside_surfaces, as the truth). Version 5: an OVDF
// sample is inside the part when it is inside one of the part's closed
// pieces (src/fields/solid_pieces.h), so a sample inside overlapping pieces (a
// waist sunk into a pelvis) or a clockwise-wound mesh is no longer traced
// from inside them. Version 6: OVDF shells inside the bounding sphere hold
// the whole sphere of directions (zoom 1/√2, shading_core.h ovdf_zoom), so
// that directions away from the part's centre are traced, not the horizon's
// edge texels. Version 7: OVDF files end with the radial spans
// (src/fields/ovdf_spans.h), the receiver's inside test. Version 8: OVDF files
// hold each sample's occluded area (shading::ovdf_area_bound), and a sample
// is inside the part when 12 of its 14 probes leave it from behind, whether
// or not the others escape through a hole (src/fields/solid_pieces.h).
inline constexpr uint32_t kFieldFormatVersion = 8;
inline constexpr int kMostSpanResolution = 1024;
enum class FieldKind : uint32_t { Svdf = 1, Ovdf = 2 };

// Positions, normals, tangents and indices: everything the tables depend on.
uint64_t mesh_hash(const TriangleMesh& mesh);

std::string params_json(const SvdfParams& params);
std::string params_json(const OvdfParams& params);
inline uint64_t params_hash(const std::string& json) { return fnv1a64(json.data(), json.size()); }

struct FieldHeader {
    uint32_t version = 0;
    FieldKind kind = FieldKind::Svdf;
    uint64_t mesh_hash = 0, params_hash = 0;
    std::string params;  // JSON
    int dims = 0, vectors = 0, clusters = 0, samples = 0;
    bool half_tables = false;
    uint64_t checksum = 0;
    size_t file_bytes = 0;
};

// What a reader expects; a mismatch is refused as stale.
struct FieldExpectation {
    std::optional<uint64_t> mesh_hash;
    std::optional<std::string> params;  // JSON, compared by hash
};

void write_svdf(const std::filesystem::path& path, const Svdf& svdf, uint64_t mesh_hash);
void write_ovdf(const std::filesystem::path& path, const Ovdf& ovdf, uint64_t mesh_hash);

Svdf read_svdf(const std::filesystem::path& path, const FieldExpectation& expect = {});
Ovdf read_ovdf(const std::filesystem::path& path, const FieldExpectation& expect = {});

// Header of any field file, after checking magic, size, checksum and version.
FieldHeader read_field_header(const std::filesystem::path& path);

}  // namespace rsl
