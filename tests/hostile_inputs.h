#pragma once
// The hostile inputs of issue 20 — what mutation fuzzing (docs/design/FUZZING.md)
// and a hostile user's review found — built the way the fuzzer made them:
// flipped bits, a corrupted header field, an out-of-range number. The
// regression tests (tests/formats/hostile_input_test.cpp,
// tests/fields/field_file_test.cpp) check how each is refused; the input
// sweep (tests/fuzz/input_sweep_test.cpp) runs every one through `rsl`.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "src/fields/field_file.h"
#include "fuzz/fixup.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "tests/radiance_encoder.h"

namespace rsl::test::hostile {

// ---- environment maps

// A flat (not run-length encoded) 64×32 Radiance file whose pixel (x=7, y=3)
// has its exponent flipped from 128 to 248: a radiance of about 5e35.
inline std::string flipped_exponent_hdr() {
    std::string bytes = encode_radiance(64, 32, std::vector<Rgbe>(64 * 32, Rgbe{100, 100, 100, 128}), false);
    const size_t pixel = size_t(3) * 64 + 7;
    const size_t exponent = bytes.size() - size_t(64 * 32 - pixel) * 4 + 3;
    bytes[exponent] = char(uint8_t(bytes[exponent]) ^ 0x78);
    return bytes;
}

// The same file with a header claiming 16000×16000 pixels (3 GB of floats).
inline std::string oversized_hdr() {
    std::string bytes = encode_radiance(64, 32, std::vector<Rgbe>(64 * 32, Rgbe{100, 100, 100, 128}), false);
    bytes.replace(bytes.find("-Y 32 +X 64"), 11, "-Y 16000 +X 16000");
    return bytes;
}

// A 64×32 EXR as write_exr writes it (through a file in `dir`).
inline std::string exr_bytes(const std::filesystem::path& dir, EnvmapKind envmap) {
    Image image(64, 32, 3);
    for (size_t k = 0; k < image.pixels.size(); ++k) image.pixels[k] = 0.01f * float(k % 97);
    write_exr(dir / "hostile_base.exr", image, {.envmap = envmap});
    return read_file(dir / "hostile_base.exr");
}

// Patches one int32 of an EXR header's box2i attribute `name` (index 0..3:
// xMin, yMin, xMax, yMax), as a bit flip in the header would.
inline void patch_box(std::string& exr, const std::string& name, int index, int32_t value) {
    const std::string key = name + std::string(1, '\0') + "box2i" + std::string(1, '\0');
    const size_t at = exr.find(key);
    RSL_CHECK(at != std::string::npos);
    std::memcpy(exr.data() + at + key.size() + 4 + 4 * index, &value, 4);  // after the u32 attribute size
}

// Declared lat-long, data window 100001×32: 28 s and 3.4 GB before the fix.
inline std::string wide_latlong_exr(const std::filesystem::path& dir) {
    std::string bytes = exr_bytes(dir, EnvmapKind::LatLong);
    patch_box(bytes, "dataWindow", 2, 100000);
    return bytes;
}

// No layout declared, data window 1000001 wide: 384 MB of floats if believed.
inline std::string wide_plain_exr(const std::filesystem::path& dir) {
    std::string bytes = exr_bytes(dir, EnvmapKind::None);
    patch_box(bytes, "dataWindow", 2, 1000000);
    return bytes;
}

// A 64×32 EXR with one more attribute first in its header: `size` is what
// the attribute declares, `value` what follows it.
inline std::string exr_with_attribute(const std::filesystem::path& dir, const std::string& name,
                                      const std::string& type, int32_t size, const std::string& value = "") {
    std::string bytes = exr_bytes(dir, EnvmapKind::None);
    std::string attribute = name + '\0' + type + '\0';
    attribute.append(reinterpret_cast<const char*>(&size), 4);
    bytes.insert(8, attribute + value);  // after the magic number and version
    return bytes;
}

// An attribute of an unknown type claiming 2 GB (fuzz_exr found a renamed
// attribute type with a flipped size): OpenEXR allocated the 2 GB before
// reading found the file 500 bytes long.
inline std::string exr_huge_attribute(const std::filesystem::path& dir) {
    return exr_with_attribute(dir, "zz", "opaque", 0x7fff0000);
}

// A float attribute declaring 8 bytes: OpenEXR reads 4 and takes the next 4
// for the following attribute's name, so that the rest of the header is
// read out of step (how fuzz_exr's second finding reached a 1.6 GB
// allocation past a check of the declared sizes alone).
inline std::string exr_misaligned_attribute(const std::filesystem::path& dir) {
    // 1.0f, then what OpenEXR takes for an attribute "z" whose type runs into
    // the next attribute's name and whose size is "chli" (1.7 GB).
    return exr_with_attribute(dir, "ratio", "float", 8, std::string("\0\0\x80\x3f" "z\0\xff\xff", 8));
}

// ---- meshes and scenes

constexpr const char* kTetrahedronObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// A tetrahedron whose normals are finite but overflow when squared in float
// (1e30, and 3e38 in two components): normalized in float they became zero.
inline std::string huge_normals_obj() {
    return "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1e30 0 0\nvn 3e38 -3e38 0\nvn 0 0 1\n"
           "f 1//1 3//2 2//3\nf 1//1 2//3 4//2\nf 1//2 4//3 3//1\nf 2//1 3//2 4//3\n";
}

// A text glTF of one triangle whose buffer is `uri` (default: the
// triangle's three positions, embedded) and whose POSITION accessor has
// `count` elements.
inline std::string gltf_triangle(const std::string& count = "3",
                                 const std::string& uri = "data:application/octet-stream;base64,"
                                                          "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA") {
    return R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + count + R"(, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36, "byteStride": 12}],
  "buffers": [{"byteLength": 36, "uri": ")" + uri + R"("}]})";
}

// 12 × (count − 1) wraps around 2^64 to less than the view's 36 bytes, so
// the range check passed and std::vector refused the size (status 2).
inline std::string gltf_count_overflow() { return gltf_triangle("1537228672809129302"); }

// A glTF whose `extras` nest `depth` arrays deep: tinygltf's recursive
// parse overflowed the stack at 200,000 (a segfault, issue 56).
inline std::string gltf_deeply_nested(int depth = 200000) {
    return R"({"asset": {"version": "2.0"}, "extras": )" + std::string(size_t(depth), '[') +
           std::string(size_t(depth), ']') + "}";
}

// A buffer naming a directory: tinygltf took its size for 2^63 − 1 bytes
// and std::bad_alloc ended `rsl` with status 2.
inline std::string gltf_directory_buffer() { return gltf_triangle("3", "."); }

// Scene files naming part.obj (kTetrahedronObj beside them) with numbers
// beyond double range.
inline std::string overflow_scene() {
    return "{ \"parts\": [{ \"obj\": \"part.obj\" }],\n  \"camera\": { \"fov_degrees\": 1e309 } }";
}
inline std::string overflow_array_scene() {
    return "{ \"parts\": [{ \"obj\": \"part.obj\" }],\n  \"lights\": [{ \"position\": [1, 2, -1e999] }] }";
}

// ---- field files

// A valid small SVDF (the format does not care what the numbers mean) whose
// table value `nan_at` is NaN: the checksum is right, the numbers are not.
inline std::string svdf_with_nan(const std::filesystem::path& dir, size_t nan_at) {
    Svdf svdf;
    svdf.params.resolution = 2;
    svdf.params.vectors = 1;
    svdf.params.half_precision_tables = false;
    CpcaModel& m = svdf.model;
    m.dims = 4, m.vectors = 1, m.clusters = 1;
    m.tables.assign(4 * 2, 0.25f);
    m.tables[nan_at] = std::nanf("");
    m.assignment = {0, 0, 0};
    m.coefficients = {0.5f, -0.5f, 1.0f};
    write_svdf(dir / "hostile_base.rslf", svdf, 7);
    return read_file(dir / "hostile_base.rslf");
}

// A small OVDF as rsl bake writes one (an octahedron's, coarse settings).
inline std::string ovdf_bytes(const std::filesystem::path& dir) {
    TriangleMesh mesh;
    mesh.positions = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
    mesh.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    validate_and_complete(mesh, "octahedron");
    const OvdfParams params{.shells = 2, .cube_resolution = 2, .vdt_resolution = 4, .vectors = 1,
                            .segments_per_side = 1, .supersampling = 1};
    write_ovdf(dir / "hostile_base.rslf", bake_ovdf(mesh, params), mesh_hash(mesh));
    return read_file(dir / "hostile_base.rslf");
}

// A field file whose parameter block has `key` set to the JSON `value`,
// its hash and checksum made right again (as a writer with a bug would).
inline std::string with_field_parameter(const std::string& bytes, const std::string& key, const std::string& value) {
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 32, 4);
    std::string params = bytes.substr(36, length);
    const std::string quoted = "\"" + key + "\":";
    const size_t at = params.find(quoted);
    RSL_CHECK(at != std::string::npos);
    const size_t begin = at + quoted.size(), end = params.find_first_of(",}", begin);
    params.replace(begin, end - begin, value);
    const uint32_t new_length = uint32_t(params.size());
    std::string out = bytes.substr(0, 32) + std::string(reinterpret_cast<const char*>(&new_length), 4) + params +
                      bytes.substr(36 + length);
    fuzz::fix_field_file(out);
    return out;
}

// An OVDF whose bounding sphere's center has a NaN x (fuzz_rslf: the lookup
// converted a NaN shell coordinate to int, undefined behaviour).
inline std::string ovdf_nan_center(const std::filesystem::path& dir) {
    std::string bytes = ovdf_bytes(dir);
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 32, 4);
    const float nan = std::nanf("");
    std::memcpy(bytes.data() + 36 + length, &nan, 4);  // the center follows the parameters
    fuzz::fix_field_file(bytes);
    return bytes;
}

}  // namespace rsl::test::hostile
