// Seed corpora of the fuzzers: see seeds.h.
#include "fuzz/seeds/seeds.h"

#include <cstring>
#include <sstream>

#include "src/formats/gltf_model.h"  // tinygltf, configured as the loader compiles it

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfEnvmapAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <nlohmann/json.hpp>

#include "tools/assets/environments.h"
#include "tools/assets/model.h"
#include "tools/assets/primitives.h"
#include "src/fields/field_file.h"
#include "src/fields/ovdf_spans.h"
#include "src/fields/solid_pieces.h"
#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "src/formats/json_file.h"
#include "src/formats/vertex_colors.h"
#include "tests/radiance_encoder.h"

namespace rsl::fuzz {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A closed tetrahedron: comments, an object name, normals, `v//n` corners.
constexpr const char* kTetrahedronObj =
    "# a tetrahedron\no tet\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "vn -0.577 -0.577 -0.577\nvn 0.577 0.577 0.577\n"
    "f 1//1 3//1 2//1\nf 1//1 2//1 4//1\nf 1//1 4//1 3//1\nf 2//2 3//2 4//2\n";

// A unit box of quads (fan-triangulated) with texture coordinates, `v/t/n`
// and `v/t` corners, negative (relative) indices and the lines the reader skips.
constexpr const char* kBoxObj =
    "mtllib box.mtl\ng box\ns 1\nusemtl grey\n"
    "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 1 -0.5\nv -0.5 1 -0.5\n"
    "v -0.5 0 0.5\nv 0.5 0 0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 -1\nvn 0 0 1\n"
    "f 1/1/1 4/4/1 3/3/1 2/2/1\nf 5/1/2 6/2/2 7/3/2 8/4/2\n"
    "f 1/1 5/2 8/3 4/4\nf 2 3 7 6\nf -5 -1 -2 -6\nf -8 -7 -3 -4\n"
    "l 1 2\np 3\n";

// A closed solid of revolution with `segments` vertices per ring and a
// `rings`-sample profile from pole to pole: with 4 and 3, an octahedron.
// The seeds' meshes stay this small so that the files stay a few KB.
TriangleMesh small_solid(int segments, int rings, float radius) {
    std::vector<assets::ProfileSample> profile;
    for (int k = 0; k < rings; ++k) {
        const float angle = 3.14159265f * (float(k) / float(rings - 1) - 0.5f);
        const Vec2 normal(std::cos(angle), std::sin(angle));
        profile.push_back({radius * normal, normal});
    }
    profile.front().point.x = profile.back().point.x = 0;  // exactly on the axis: single pole vertices
    return assets::revolve(profile, segments);
}

// A small two-node model with a looping animation (the robot's structure in
// a few hundred bytes of geometry): a rounded box and a sphere on an arm.
assets::GeneratedModel small_model() {
    assets::GeneratedModel model;
    model.animation_name = "swing";
    model.loop_seconds = 1;
    const int body = model.add_node("body", -1, Vec3(0, 0.5f, 0), small_solid(6, 4, 0.3f));
    const int arm = model.add_node("arm", body, Vec3(0.5f, 0.2f, 0), small_solid(4, 3, 0.15f));
    model.scene.nodes[body].translation =
        assets::loop_translation_track([](float t) { return Vec3(0, 0.5f + 0.1f * std::sin(6.2831853f * t), 0); }, 1, 4);
    model.scene.nodes[arm].rotation = assets::loop_rotation_track(
        [](float t) { return glm::angleAxis(0.5f * std::sin(6.2831853f * t), Vec3(0, 0, 1)); }, 1, 4);
    return model;
}

// A static single-node model.
assets::GeneratedModel single_model() {
    assets::GeneratedModel model;
    model.add_node("ball", -1, Vec3(0), small_solid(5, 4, 0.4f));
    return model;
}

// The same model as text glTF (buffers embedded as data URIs), through
// tinygltf; `interpolation`, when given, replaces every sampler's.
void write_gltf_from_glb(const fs::path& glb, const fs::path& gltf, const std::string& interpolation = "") {
    tinygltf::TinyGLTF io;
    tinygltf::Model model;
    std::string error, warning;
    if (!io.LoadBinaryFromFile(&model, &error, &warning, glb.string())) throw_file_error(glb, "{}", error);
    for (tinygltf::Animation& animation : model.animations)
        for (tinygltf::AnimationSampler& sampler : animation.samplers)
            if (!interpolation.empty()) sampler.interpolation = interpolation;
    std::ostringstream stream;
    if (!io.WriteGltfSceneToStream(&model, stream, true, false)) throw_file_error(gltf, "tinygltf could not write it");
    write_file_atomically(gltf, stream.str());
}

// `depth` arrays nested around one small object (`depth` 0: the object alone), with a
// string of brackets inside, which the depth check must not count as nesting.
json nested_arrays(int depth) {
    json value = {{"brackets", "[[{{\"x\": ]]"}};
    for (int level = 0; level < depth; ++level) value = json::array({value});
    return value;
}

// The glTF seed `gltf` with `extras` on the asset nested to the depth limit
// of the glTF reader (kMaxGltfJsonDepth, 256: the root object, the asset and
// 253 arrays around the innermost object).
json at_depth_limit(json gltf) {
    gltf["asset"]["extras"] = nested_arrays(253);
    return gltf;
}

// A .glb whose JSON chunk is replaced by `chunk` (padded with spaces to 4
// bytes, as the format requires), its binary chunk kept.
std::string glb_with_json(const std::string& glb, std::string chunk) {
    chunk.resize((chunk.size() + 3) / 4 * 4, ' ');
    uint32_t old_length = 0;
    std::memcpy(&old_length, glb.data() + 12, 4);
    const std::string binary = glb.substr(20 + old_length);
    std::string out = glb.substr(0, 12);
    const uint32_t length = uint32_t(chunk.size());
    out.append(reinterpret_cast<const char*>(&length), 4).append("JSON").append(chunk).append(binary);
    const uint32_t total = uint32_t(out.size());
    std::memcpy(out.data() + 8, &total, 4);
    return out;
}

// An EXR with a chosen compression (write_exr always uses ZIP), so that the
// seeds reach OpenEXR's other decoders.
void write_exr_compressed(const fs::path& path, const Image& image, Imf::Compression compression) {
    write_atomically(path, [&](const fs::path& tmp) {
        Imf::Header header(image.width, image.height);
        header.compression() = compression;
        const char* names[] = {"R", "G", "B", "A"};
        Imf::FrameBuffer frame;
        const size_t x_stride = sizeof(float) * image.channels;
        for (int c = 0; c < image.channels; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)&image.pixels[c], x_stride, x_stride * image.width));
        }
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    });
}

// A w × 6w vertical cube strip, each face a different gradient.
Image cube_strip(int w) {
    Image image(w, 6 * w, 3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < w; ++x)
            image.set_rgb(x, y, Color(0.1f + 0.1f * float(y / w), float(x) / float(w), float(y % w) / float(w)));
    return image;
}

// A rendered frame's shape: RGBA (alpha = coverage), not an environment layout.
Image rendered_frame() {
    Image image(12, 8, 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 12; ++x) {
            float* p = image.at(x, y);
            p[3] = x < 9 ? 1.0f : 0.0f;
            p[0] = p[3] * 0.05f * float(x), p[1] = p[3] * 0.1f * float(y), p[2] = p[3] * 0.3f;
        }
    return image;
}

// A scene file of assets/scenes with every file it names replaced by the
// stand-ins of write_scene_support_files, and part names by the stand-ins'.
json scene_with_stand_ins(json scene) {
    std::vector<std::string> part_names;  // the names the stand-ins give the parts
    if (scene.contains("gltf")) {
        scene["gltf"] = "part.glb";
        part_names = {"body", "arm"};
    }
    if (scene.contains("parts"))
        for (json& part : scene["parts"]) {
            if (part.contains("obj")) part["obj"] = "part.obj";
            if (part.contains("gltf")) part["gltf"] = "part.gltf";
            part_names.push_back(part.value("name", part.contains("obj") ? "part" : "body"));
        }
    if (scene.contains("part_materials")) {
        // Keys the stand-ins have keep their material; the others move to an unused stand-in part.
        json renamed = json::object();
        size_t next = 0;
        for (const auto& [name, material] : scene["part_materials"].items()) {
            const bool known = name == "*" || std::find(part_names.begin(), part_names.end(), name) != part_names.end();
            while (!known && next < part_names.size() && renamed.contains(part_names[next])) ++next;
            if (known) renamed[name] = material;
            else if (next < part_names.size()) renamed[part_names[next++]] = material;
        }
        scene["part_materials"] = renamed;
    }
    if (scene.contains("environment")) {
        scene["environment"]["file"] = "env.exr";
        if (scene["environment"].contains("second_file")) scene["environment"]["second_file"] = "env.hdr";
    }
    return scene;
}

// Every key of docs/SCENE_FORMAT.md once, with obj and glTF parts.
constexpr const char* kEveryKeyScene = R"({
  "name": "every_key",
  "gltf": "part.glb",
  "parts": [
    { "name": "tet", "obj": "part.obj",
      "transform": { "translation": [1, 0, 0], "rotation_axis_angle": [0, 1, 0, 30], "scale": [1, 2, 1] },
      "material": "floor" },
    { "name": "copy", "gltf": "part.gltf", "transform": { "scale": 0.5 } }
  ],
  "materials": {
    "default": { "model": "lambert", "albedo": [0.7, 0.7, 0.7] },
    "steel": { "model": "phong", "kd": [0.1, 0.1, 0.1], "ks": [0.6, 0.6, 0.6], "exponent": 60 },
    "floor": { "model": "ward_anisotropic", "kd": 0.4, "ks": 0.1, "alpha_x": 0.1, "alpha_y": 0.3 }
  },
  "part_materials": { "arm": "steel", "*": "default" },
  "environment": { "file": "env.exr", "resolution": 8,
                   "rotation": { "axis": [0, 1, 0], "degrees": 10, "degrees_per_second": 20 },
                   "second_file": "env.hdr", "blend_period_seconds": 4 },
  "lights": [ { "radius": 0.05, "power": [20, 18, 15], "position": [1, 2, 1],
                "path": { "times": [0, 1, 2], "positions": [[1, 2, 1], [-1, 2, 1], [1, 2, 1]] } },
              { "power": [1, 1, 1] } ],
  "camera": { "position": [0, 1.5, 5], "target": [0, 1, 0], "up": [0, 1, 0], "fov_degrees": 40,
              "width": 64, "height": 48,
              "path": { "times": [0, 2], "positions": [[0, 1.5, 5], [3, 1.5, 4]], "targets": [[0, 1, 0], [0, 1, 0]] } },
  "animation": { "start": 0, "end": 2, "fps": 24 },
  "precompute": { "svdf": { "resolution": 8, "clusters": 4, "vectors": 2, "supersampling": 1 },
                  "ovdf": { "shells": 2, "inner_radius": 0.4, "outer_radius": 6.0,
                            "cube_resolution": 4, "vdt_resolution": 8, "vectors": 2 } }
}
)";

// Values at the edges of their ranges (docs/SCENE_FORMAT.md, BRDF.md): light
// powers at and just under 10¹² W with the smallest radius the radiance limit
// allows them, roughness and alphas at 10⁻³, the largest cube map and image.
constexpr const char* kEdgesScene = R"({
  "name": "edges",
  "parts": [ { "name": "tet", "obj": "part.obj", "material": "glossy" },
             { "name": "copy", "gltf": "part.gltf", "transform": { "scale": 1e-3 }, "material": "mirror" },
             { "name": "ball", "obj": "part.obj", "transform": { "translation": [2, 0, 0] }, "material": "sharp" },
             { "name": "plain", "obj": "part.obj", "transform": { "translation": [-2, 0, 0] } } ],
  "materials": {
    "default": { "model": "ward_anisotropic", "kd": 0, "ks": 1, "alpha_x": 1e-3, "alpha_y": 1 },
    "glossy": { "model": "cook_torrance_beckmann", "f0": [1, 1, 1], "roughness": 1e-3 },
    "mirror": { "model": "cook_torrance_ggx", "f0": 0.04, "roughness": 0.001, "kd": 1 },
    "sharp": { "model": "ward", "kd": 0, "ks": 1, "alpha": 1e-3 }
  },
  "environment": { "file": "env.exr", "resolution": 512 },
  "lights": [ { "radius": 0.0504, "power": [1e12, 1e12, 1e12], "position": [1, 2, 1] },
              { "radius": 1, "power": [999999930368, 0, 1e-30], "position": [-1e6, 1e6, 0] } ],
  "camera": { "position": [0, 1.5, 5], "target": [0, 1, 0], "width": 16384, "height": 1 }
}
)";

class CorpusWriter {
public:
    explicit CorpusWriter(const fs::path& dir) : dir_(dir) {}

    fs::path path(const std::string& reader, const std::string& stem) {
        fs::path file = dir_ / reader / (stem + reader_extension(reader));
        files_.push_back(file);
        return file;
    }
    void text(const std::string& reader, const std::string& stem, std::string_view contents) {
        write_file_atomically(path(reader, stem), contents);
    }
    std::vector<fs::path> files() const { return files_; }

private:
    fs::path dir_;
    std::vector<fs::path> files_;
};

}  // namespace

const std::vector<std::string>& reader_names() {
    static const std::vector<std::string> names = {"hdr", "exr", "obj", "gltf", "glb", "scene", "rslf", "rslv"};
    return names;
}

std::string reader_extension(const std::string& reader) { return reader == "scene" ? ".json" : "." + reader; }

void write_scene_support_files(const fs::path& dir) {
    write_file_atomically(dir / "part.obj", kTetrahedronObj);
    assets::write_glb(dir / "part.glb", small_model());
    write_gltf_from_glb(dir / "part.glb", dir / "part.gltf");
    write_exr(dir / "env.exr", assets::make_sunsky({}, 16, 8), {.envmap = EnvmapKind::LatLong});
    write_file_atomically(dir / "env.hdr", test::encode_radiance(assets::make_overcast(16, 8), true));
}

std::vector<fs::path> write_seed_corpora(const fs::path& dir, const fs::path& source_dir) {
    CorpusWriter out(dir);

    // Environment maps: Radiance RLE and flat, a header with EXPOSURE; EXR lat-long, half, cube strip,
    // a rendered RGBA frame, and the other compressions.
    const Image sunsky = assets::make_sunsky({}, 32, 16);
    out.text("hdr", "sunsky_rle", test::encode_radiance(sunsky, true));
    out.text("hdr", "studio_flat", test::encode_radiance(assets::make_studio(16, 8), false));
    std::string exposed = test::encode_radiance(assets::make_overcast(16, 8), true);
    exposed.insert(exposed.find("FORMAT="), "EXPOSURE=2.5\n");
    out.text("hdr", "overcast_exposure", exposed);
    out.text("hdr", "strip_rle", test::encode_radiance(cube_strip(8), true));

    write_exr(out.path("exr", "sunsky_latlong"), sunsky, {.envmap = EnvmapKind::LatLong});
    write_exr(out.path("exr", "studio_half"), assets::make_studio(16, 8), {.half = true});
    write_exr(out.path("exr", "strip_cube"), cube_strip(4), {.envmap = EnvmapKind::Cube});
    write_exr(out.path("exr", "rendered_rgba"), rendered_frame());
    const Image overcast = assets::make_overcast(8, 4);
    write_exr_compressed(out.path("exr", "overcast_none"), overcast, Imf::NO_COMPRESSION);
    write_exr_compressed(out.path("exr", "overcast_rle"), overcast, Imf::RLE_COMPRESSION);
    write_exr_compressed(out.path("exr", "overcast_piz"), overcast, Imf::PIZ_COMPRESSION);
    write_exr_compressed(out.path("exr", "overcast_pxr24"), overcast, Imf::PXR24_COMPRESSION);

    // Meshes.
    out.text("obj", "tetrahedron", kTetrahedronObj);
    out.text("obj", "box_quads", kBoxObj);
    assets::write_obj(out.path("obj", "solid"), small_solid(6, 5, 0.5f));
    assets::write_glb(out.path("glb", "animated"), small_model());
    assets::write_glb(out.path("glb", "single"), single_model());
    write_gltf_from_glb(dir / "glb" / "animated.glb", out.path("gltf", "animated"));
    write_gltf_from_glb(dir / "glb" / "animated.glb", out.path("gltf", "animated_step"), "STEP");
    write_gltf_from_glb(dir / "glb" / "single.glb", out.path("gltf", "single"));
    out.text("gltf", "depth_limit", at_depth_limit(read_json_file(dir / "gltf" / "single.gltf")).dump() + "\n");
    const std::string single_glb = read_file(dir / "glb" / "single.glb");
    uint32_t json_length = 0;
    std::memcpy(&json_length, single_glb.data() + 12, 4);
    out.text("glb", "depth_limit",
             glb_with_json(single_glb, at_depth_limit(json::parse(single_glb.substr(20, json_length))).dump()));

    // Scene files: the project's, pointed at the stand-ins, and one with every key.
    for (const char* name : {"default", "robot", "kitchen", "bunny"}) {
        const fs::path source = source_dir / "assets" / "scenes" / (std::string(name) + ".json");
        out.text("scene", name, scene_with_stand_ins(read_json_file(source)).dump(1) + "\n");
    }
    out.text("scene", "every_key", kEveryKeyScene);
    out.text("scene", "edges", kEdgesScene);

    // Field files baked on a small sphere: SVDF with half and float tables, an OVDF.
    const TriangleMesh ball = small_solid(6, 5, 0.5f);
    SvdfParams svdf{.resolution = 4, .supersampling = 1, .clusters = 2, .vectors = 2};
    write_svdf(out.path("rslf", "svdf_half"), bake_svdf(ball, svdf), mesh_hash(ball));
    svdf.half_precision_tables = false;
    write_svdf(out.path("rslf", "svdf_float"), bake_svdf(ball, svdf), mesh_hash(ball));
    const OvdfParams ovdf{.shells = 2, .cube_resolution = 2, .vdt_resolution = 4, .vectors = 2,
                          .segments_per_side = 1, .supersampling = 1};
    // Its radial spans at 8² lines a face, not the build's 256² (3 MB): the
    // file holds its own resolution, and the seed stays a few kilobytes.
    Ovdf small = bake_ovdf(ball, ovdf);
    small.span_resolution = 8;
    small.radial_span = bake_radial_spans(SolidPieces(ball), small.center, small.radius, small.span_resolution);
    write_ovdf(out.path("rslf", "ovdf"), small, mesh_hash(ball));

    // Vertex colours: two parts, and none.
    VertexColors colors;
    colors.scene_name = "seed", colors.producer = "fuzz seeds", colors.time = 0.5f;
    colors.add_part("ground", 3);
    colors.add_part("box", 5);
    for (size_t v = 0; v < 5; ++v) colors.parts[1][v] = Color(0.1f * float(v), 0.5f, 2.0f);
    write_vertex_colors(out.path("rslv", "two_parts"), colors);
    colors = VertexColors();
    colors.scene_name = "empty", colors.producer = "fuzz seeds";
    write_vertex_colors(out.path("rslv", "empty"), colors);
    return out.files();
}

}  // namespace rsl::fuzz
