// The project's own assets (tools/assets): solids are closed with outward
// analytic normals and the volumes of their formulas, the models have the
// part and vertex counts the paper's scenes have, the animations move and
// loop, the environments carry their energy where they should, the files
// round-trip through the loaders, and the scene files load.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <unordered_map>

#include <catch2/catch.hpp>
#include <unistd.h>

#include "tools/assets/environments.h"
#include "tools/assets/generate_all.h"
#include "tools/assets/kitchen.h"
#include "tools/assets/primitives.h"
#include "tools/assets/robot.h"
#include "src/core/atomic_file.h"
#include "src/core/envmap.h"
#include "src/formats/image_file.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"

using namespace rsl;
using namespace rsl::assets;
namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------- mesh checks

// Closed and consistently oriented: every directed edge appears exactly once
// and its reverse exactly once (a closed, edge-manifold, oriented surface).
bool closed_and_oriented(const TriangleMesh& mesh) {
    std::unordered_map<uint64_t, int> directed;
    const auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
        for (int e = 0; e < 3; ++e) ++directed[key(mesh.indices[3 * t + e], mesh.indices[3 * t + (e + 1) % 3])];
    for (const auto& [edge, count] : directed) {
        if (count != 1) return false;
        const auto reverse = directed.find(key(uint32_t(edge & 0xffffffffu), uint32_t(edge >> 32)));
        if (reverse == directed.end() || reverse->second != 1) return false;
    }
    return true;
}

double signed_volume(const TriangleMesh& mesh) {
    double v = 0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const DVec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                    c = mesh.positions[mesh.indices[3 * t + 2]];
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

// Triangles whose winding disagrees with the stored (analytic) vertex normals.
size_t triangles_facing_against_normals(const TriangleMesh& mesh) {
    size_t bad = 0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
        const Vec3 face = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        if (glm::dot(face, mesh.normals[a] + mesh.normals[b] + mesh.normals[c]) <= 0) ++bad;
    }
    return bad;
}

// Largest angle (degrees) between a stored normal and the area-weighted normal
// of the triangles around it: small when the normals are the surface's own.
float max_normal_deviation_degrees(const TriangleMesh& mesh) {
    std::vector<Vec3> sum(mesh.vertex_count(), Vec3(0));
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
        const Vec3 face = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        for (uint32_t v : {a, b, c}) sum[v] += face;
    }
    float worst = 0;
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const float cosine = glm::dot(glm::normalize(sum[v]), mesh.normals[v]);
        worst = std::max(worst, std::acos(std::clamp(cosine, -1.0f, 1.0f)) * 180 / kPi);
    }
    return worst;
}

void check_frames(const TriangleMesh& mesh) {
    REQUIRE(mesh.normals.size() == mesh.vertex_count());
    REQUIRE(mesh.tangents.size() == mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Vec3 t(mesh.tangents[v]);
        REQUIRE(glm::length(mesh.normals[v]) == Approx(1).margin(1e-4));
        REQUIRE(glm::length(t) == Approx(1).margin(1e-4));
        REQUIRE(std::abs(glm::dot(t, mesh.normals[v])) < 1e-4f);
        REQUIRE(std::abs(mesh.tangents[v].w) == 1.0f);
    }
}

void check_closed_solid(const TriangleMesh& mesh, float max_deviation_degrees = 20) {
    INFO("part " << mesh.name);
    CHECK(closed_and_oriented(mesh));
    CHECK(signed_volume(mesh) > 0);
    CHECK(triangles_facing_against_normals(mesh) == 0);
    CHECK(max_normal_deviation_degrees(mesh) < max_deviation_degrees);
    check_frames(mesh);
}

const Part& part_named(const Scene& scene, const std::string& name) {
    for (const Part& p : scene.parts)
        if (p.name == name) return p;
    FAIL("no part named " << name);
    throw;
}

int part_index(const Scene& scene, const std::string& name) { return int(&part_named(scene, name) - scene.parts.data()); }

Vec3 world_center(const Scene& scene, int part, float t) {
    return Vec3(scene.part_transform_at(part, t) * Vec4(scene.parts[part].mesh.bounding_sphere().center, 1));
}

float max_matrix_difference(const Mat4& a, const Mat4& b) {
    float d = 0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
    return d;
}

// Every part's world transform at t equals the one at t + period (the last key
// repeats the first), and the motion is continuous across the wrap.
void check_loops(const GeneratedModel& model) {
    const Scene& s = model.scene;
    const float T = model.loop_seconds;
    for (size_t p = 0; p < s.parts.size(); ++p) {
        INFO("part " << s.parts[p].name);
        CHECK(max_matrix_difference(s.part_transform_at(int(p), 0), s.part_transform_at(int(p), T)) < 1e-5f);
        const float dt = T / 1000;
        CHECK(glm::distance(world_center(s, int(p), T - dt), world_center(s, int(p), dt)) < 0.01f);
    }
}

// Largest distance a part's centre travels from its position at t = 0 over one loop.
float excursion(const GeneratedModel& model, const std::string& part) {
    const int p = part_index(model.scene, part);
    const Vec3 start = world_center(model.scene, p, 0);
    float far = 0;
    for (int k = 1; k < 64; ++k) far = std::max(far, glm::distance(start, world_center(model.scene, p, model.loop_seconds * k / 64)));
    return far;
}

// ---------------------------------------------------------------- files

// One generated folder per test run, laid out like the repository
// (root/assets/{generated,scenes}) with base/shared pointing at the shared
// assets, so the scene files' relative paths resolve exactly as in the tree.
struct GeneratedTree {
    fs::path base, root, generated, scenes;
    GenerateReport first_report;

    GeneratedTree() {
        base = fs::temp_directory_path() / ("rsl_generated_assets_test_" + std::to_string(getpid()));
        root = base / "rsl";
        generated = root / "assets" / "generated";
        scenes = root / "assets" / "scenes";
        fs::remove_all(base);
        fs::create_directories(scenes);
        // The scene files only: a field cache (.rsl-cache/) may sit beside them.
        for (const auto& entry : fs::directory_iterator(fs::path(RSL_SOURCE_DIR) / "assets" / "scenes"))
            if (entry.is_regular_file() && entry.path().extension() == ".json")
                fs::copy_file(entry.path(), scenes / entry.path().filename());
        if (fs::exists(RSL_SHARED_ASSETS)) fs::create_directory_symlink(fs::absolute(RSL_SHARED_ASSETS).parent_path(), base / "shared");
        first_report = generate_assets(generated);
    }
    ~GeneratedTree() {
        std::error_code ec;
        fs::remove_all(base, ec);
    }
};

const GeneratedTree& tree() {
    static const GeneratedTree instance;
    return instance;
}

const GeneratedModel& robot() {
    static const GeneratedModel model = make_robot();
    return model;
}

const GeneratedModel& kitchen() {
    static const GeneratedModel model = make_kitchen();
    return model;
}

}  // namespace

// ---------------------------------------------------------------- primitives

TEST_CASE("primitives: closed, outward, with the volumes of their formulas", "[assets]") {
    const double pi = std::numbers::pi;
    SECTION("sphere") {
        const TriangleMesh m = sphere(0.3f, 0.01f);
        check_closed_solid(m);
        CHECK(signed_volume(m) == Approx(4.0 / 3 * pi * 0.027).epsilon(0.005));
        for (size_t v = 0; v < m.vertex_count(); ++v)  // the analytic normal of a sphere is its radial direction
            REQUIRE(glm::distance(m.normals[v], m.positions[v] / 0.3f) < 1e-5f);
    }
    SECTION("capsule and the equal-radius round cone") {
        const double r = 0.05, half = 0.1, expected = pi * r * r * 2 * half + 4.0 / 3 * pi * r * r * r;
        const TriangleMesh c = capsule(float(r), float(half), 0.004f);
        check_closed_solid(c);
        CHECK(signed_volume(c) == Approx(expected).epsilon(0.005));
        const TriangleMesh rc = round_cone(float(r), float(r), float(2 * half), 0.004f);
        check_closed_solid(rc);
        CHECK(signed_volume(rc) == Approx(expected).epsilon(0.005));
    }
    SECTION("tapered round cone lies between its two spheres' capsules") {
        const TriangleMesh m = round_cone(0.08f, 0.04f, 0.3f, 0.005f);
        check_closed_solid(m);
        const double small = pi * 0.0016 * 0.3 + 4.0 / 3 * pi * 0.04 * 0.0016, big = pi * 0.0064 * 0.3 + 4.0 / 3 * pi * 0.08 * 0.0064;
        CHECK(signed_volume(m) > small);
        CHECK(signed_volume(m) < big);
        for (const Vec3& p : m.positions) REQUIRE((p.y > -0.0801f && p.y < 0.3401f));
    }
    SECTION("rounded box") {
        const double a = 0.25, b = 0.15, c = 0.05, r = 0.05;  // core half extents and rounding
        const double expected = 8 * a * b * c + 8 * r * (a * b + b * c + c * a) + 2 * pi * r * r * (a + b + c) +
                                4.0 / 3 * pi * r * r * r;
        const TriangleMesh m = rounded_box(Vec3(0.3f, 0.2f, 0.1f), 0.05f, 0.008f);
        check_closed_solid(m);
        CHECK(signed_volume(m) == Approx(expected).epsilon(0.005));
        const Bounds bounds = m.bounds();
        CHECK(bounds.hi.x == Approx(0.3f).margin(1e-5));
        CHECK(bounds.lo.z == Approx(-0.1f).margin(1e-5));
    }
    SECTION("torus") {
        const TriangleMesh m = torus(0.2f, 0.05f, 0.005f);
        check_closed_solid(m);
        CHECK(signed_volume(m) == Approx(2 * pi * pi * 0.2 * 0.0025).epsilon(0.005));
    }
    SECTION("lathe of a rounded polyline: volume by Pappus from the profile polygon") {
        Profile p(Vec2(0, 0));
        p.rounded_polyline({{0.05f, 0.0f}, {0.06f, 0.1f}, {0.055f, 0.1f}, {0.045f, 0.01f}, {0.0f, 0.01f}}, 0.004f);
        const auto samples = p.sample(0.002f);
        // V = 2π ∬ r dA over the profile polygon closed along the axis.
        double moment = 0;
        for (size_t i = 0; i < samples.size(); ++i) {
            const Vec2 u = samples[i].point, w = samples[(i + 1) % samples.size()].point;
            moment += (u.x + w.x) * (double(u.x) * w.y - double(w.x) * u.y) / 6;
        }
        const int segments = segments_for(samples, 0.002f);
        const TriangleMesh m = revolve(samples, segments);
        check_closed_solid(m, 40);  // the thin rim turns 180° in a few samples
        // The ring polygon inscribed in each circle scales r² by sin(2π/n)/(2π/n).
        const double ring = std::sin(2 * pi / segments) / (2 * pi / segments);
        CHECK(signed_volume(m) == Approx(2 * pi * moment * ring).epsilon(1e-4));
    }
    SECTION("grid plane is an open sheet facing +Y") {
        const TriangleMesh m = grid_plane(2, 1, 20, 10);
        CHECK(m.vertex_count() == 21 * 11);
        CHECK(triangles_facing_against_normals(m) == 0);
        CHECK(!closed_and_oriented(m));
        check_frames(m);
    }
}

// ---------------------------------------------------------------- robot

TEST_CASE("robot: 12 closed parts, about 60k vertices, in a hierarchy", "[assets]") {
    const GeneratedModel& m = robot();
    const Scene& s = m.scene;
    REQUIRE(s.parts.size() == 12);
    CHECK(m.vertex_count() >= 50000);
    CHECK(m.vertex_count() <= 70000);
    for (const Part& p : s.parts) {
        check_closed_solid(p.mesh);
        CHECK(p.mesh.vertex_count() > 1500);  // every part resolves the shadows it receives
    }
    // Hierarchy: torso is the root; hands hang from forearms from upper arms from the torso.
    const auto parent_name = [&](const std::string& part) {
        return s.nodes[s.nodes[part_named(s, part).node].parent].name;
    };
    CHECK(s.nodes[part_named(s, "torso").node].parent == -1);
    CHECK(parent_name("hand_l") == "forearm_l");
    CHECK(parent_name("forearm_r") == "upper_arm_r");
    CHECK(parent_name("shin_l") == "thigh_l");
    CHECK(parent_name("thigh_r") == "torso");
    CHECK(parent_name("head") == "torso");
}

TEST_CASE("robot: the walk moves every limb, loops, and keeps the feet on the ground", "[assets]") {
    const GeneratedModel& m = robot();
    const Scene& s = m.scene;
    CHECK(m.loop_seconds == kRobotWalkSeconds);
    check_loops(m);
    CHECK(excursion(m, "hand_l") > 0.15f);
    CHECK(excursion(m, "shin_r") > 0.15f);
    CHECK(excursion(m, "head") > 0.01f);  // the bob
    CHECK(excursion(m, "head") < 0.1f);

    // Left and right run half a loop apart.
    const int thigh_l = part_named(s, "thigh_l").node, thigh_r = part_named(s, "thigh_r").node;
    for (float t : {0.1f, 0.45f, 0.9f}) {  // t + T/2 stays inside the loop
        const Quat a = s.nodes[thigh_l].local_at(t).rotation, b = s.nodes[thigh_r].local_at(t + m.loop_seconds / 2).rotation;
        CHECK(std::abs(glm::dot(a, b)) == Approx(1).margin(1e-4));
    }
    // The lowest sole point stays within a few millimetres of the ground all loop.
    const int shins[2] = {part_index(s, "shin_l"), part_index(s, "shin_r")};
    for (int k = 0; k < 32; ++k) {
        const float t = m.loop_seconds * k / 32;
        float lowest = 1e9f;
        for (int p : shins) {
            const Mat4 world = s.part_transform_at(p, t);
            for (const Vec3& v : s.parts[p].mesh.positions) lowest = std::min(lowest, (world * Vec4(v, 1)).y);
        }
        INFO("t = " << t);
        CHECK(lowest > -0.005f);
        CHECK(lowest < 0.01f);
    }
}

TEST_CASE("ground: a finely tessellated 8 m sheet", "[assets]") {
    const TriangleMesh g = make_ground();
    CHECK(g.vertex_count() == 161 * 161);
    CHECK(g.bounds().hi.x == Approx(4));
    CHECK(g.bounds().lo.z == Approx(-4));
    CHECK(triangles_facing_against_normals(g) == 0);
    check_frames(g);
}

// ---------------------------------------------------------------- kitchen

TEST_CASE("kitchen: 5 parts, about 80k vertices, closed tableware, a looping animation", "[assets]") {
    const GeneratedModel& m = kitchen();
    const Scene& s = m.scene;
    REQUIRE(s.parts.size() == 5);
    CHECK(m.vertex_count() >= 65000);
    CHECK(m.vertex_count() <= 95000);
    for (const char* name : {"teapot", "bowl", "cup", "chair"}) check_closed_solid(part_named(s, name).mesh, 40);
    // The room is an open floor sheet plus the closed counter: it faces outwards but has a boundary.
    CHECK(triangles_facing_against_normals(part_named(s, "room").mesh) == 0);
    check_loops(m);
    CHECK(excursion(m, "teapot") > 0.1f);
    CHECK(excursion(m, "cup") > 0.1f);
    CHECK(excursion(m, "bowl") == 0.0f);
    // Tableware stands on the counter top, the chair on the floor.
    for (const char* name : {"teapot", "bowl", "cup"}) {
        const Part& p = part_named(s, name);
        CHECK(Vec3(s.part_transform_at(int(&p - s.parts.data()), 0) * Vec4(p.mesh.bounds().lo, 1)).y ==
              Approx(kCounterTop).margin(1e-4));
    }
}

// ---------------------------------------------------------------- environments

namespace {
double pixel_solid_angle(const Image& image, int y) {
    const double top = latlong_direction(0, float(y) / image.height).y, bottom = latlong_direction(0, float(y + 1) / image.height).y;
    return 2 * std::numbers::pi / image.width * (top - bottom);
}
Vec3 pixel_direction(const Image& image, int x, int y) {
    return latlong_direction((x + 0.5f) / image.width, (y + 0.5f) / image.height);
}
// Largest relative luminance step between 4-neighbours (with the u wrap).
float max_neighbour_step(const Image& image) {
    float worst = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float l = luminance(image.rgb(x, y));
            for (const auto& [nx, ny] : {std::pair{(x + 1) % image.width, y}, std::pair{x, std::min(y + 1, image.height - 1)}}) {
                const float n = luminance(image.rgb(nx, ny));
                worst = std::max(worst, std::abs(l - n) / std::max(l, n));
            }
        }
    return worst;
}
}  // namespace

TEST_CASE("sunsky: a 0.5-degree sun carries 75% of the energy", "[assets]") {
    const Image img = read_exr(tree().generated / "sunsky.exr");
    REQUIRE(img.width == kEnvironmentWidth);
    REQUIRE(img.height == kEnvironmentHeight);
    const Vec3 sun = SunSky{}.sun_direction;
    double total = 0, near_sun = 0, near_solid_angle = 0;
    float brightest = 0;
    Vec3 brightest_direction(0);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Vec3 d = pixel_direction(img, x, y);
            const double e = luminance(img.rgb(x, y)) * pixel_solid_angle(img, y);
            total += e;
            if (glm::dot(d, sun) > std::cos(1.5 * std::numbers::pi / 180)) {
                near_sun += e;
                near_solid_angle += pixel_solid_angle(img, y);
            }
            if (luminance(img.rgb(x, y)) > brightest) {
                brightest = luminance(img.rgb(x, y));
                brightest_direction = d;
            }
        }
    CHECK(near_sun / total == Approx(0.75).margin(0.01));
    CHECK(near_solid_angle < 4e-3);  // 0.03% of the sphere
    CHECK(std::acos(glm::dot(brightest_direction, sun)) * 180 / kPi < 0.7f);  // within a pixel of the sun's centre
    CHECK(luminance(Color(latlong_energy(img))) == Approx(total).epsilon(1e-5));
    CHECK(max_neighbour_step(img) > 0.9f);  // all-frequency: the sun's edge is a step
}

TEST_CASE("studio: three softboxes of the stated sizes and radiances on a dark room", "[assets]") {
    const Image img = read_exr(tree().generated / "studio.exr");
    // Connected bright regions (4-neighbours, wrapping in u) by union-find.
    const int w = img.width, h = img.height;
    std::vector<int> parent(size_t(w) * h);
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    const auto bright = [&](int x, int y) { return luminance(img.rgb(x, y)) > 0.3f; };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!bright(x, y)) continue;
            if (bright((x + 1) % w, y)) parent[find(y * w + x)] = find(y * w + (x + 1) % w);
            if (y + 1 < h && bright(x, y + 1)) parent[find(y * w + x)] = find((y + 1) * w + x);
        }
    std::map<int, DVec3> energy;  // per region root
    double dark_max = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (bright(x, y)) energy[find(y * w + x)] += DVec3(img.rgb(x, y)) * pixel_solid_angle(img, y);
            else dark_max = std::max(dark_max, double(luminance(img.rgb(x, y))));
        }
    REQUIRE(energy.size() == 3);
    CHECK(dark_max < 0.3);
    for (const Softbox& box : studio_softboxes()) {
        const Vec2 uv = latlong_coords(box.center);
        const int root = find(std::min(int(uv.y * h), h - 1) * w + std::min(int(uv.x * w), w - 1));
        REQUIRE(energy.count(root) == 1);
        // A rectangle of half angles α, β seen from its centre spans 4 asin(sin α sin β).
        const double a = box.half_width_degrees * std::numbers::pi / 180, b = box.half_height_degrees * std::numbers::pi / 180;
        const double solid_angle = 4 * std::asin(std::sin(a) * std::sin(b));
        INFO("softbox at " << box.center.x << " " << box.center.y << " " << box.center.z);
        CHECK(energy[root].r == Approx(box.radiance.r * solid_angle).epsilon(0.03));
        CHECK(energy[root].b == Approx(box.radiance.b * solid_angle).epsilon(0.03));
    }
}

TEST_CASE("overcast: the CIE overcast sky, smooth everywhere", "[assets]") {
    const Image img = read_exr(tree().generated / "overcast.exr");
    const float zenith = luminance(img.rgb(0, 0)) / ((1 + 2 * pixel_direction(img, 0, 0).y) / 3);
    for (int y = 0; y < img.height; y += 3)
        for (int x = 0; x < img.width; x += 7) {
            const Vec3 d = pixel_direction(img, x, y);
            if (d.y <= 0) continue;
            REQUIRE(luminance(img.rgb(x, y)) == Approx(zenith * (1 + 2 * d.y) / 3).epsilon(1e-4));
        }
    CHECK(max_neighbour_step(img) < 0.05f);
}

// ---------------------------------------------------------------- files

TEST_CASE("rsl assets: writes every file, then a stamp, and does nothing while the stamp matches", "[assets]") {
    const GeneratedTree& t = tree();
    CHECK(t.first_report.regenerated);
    for (const std::string& name : generated_file_names()) CHECK(fs::file_size(t.generated / name) > 0);
    for (const auto& entry : fs::directory_iterator(t.generated))  // no temporary files left behind
        CHECK(entry.path().filename().string().find(".rsl-tmp-") == std::string::npos);
    CHECK(read_file(t.generated / kStampName) == std::string(kAssetsVersion) + "\n");

    const fs::path dir = t.base / "again";
    fs::create_directories(dir);
    for (const auto& entry : fs::directory_iterator(t.generated)) fs::copy_file(entry.path(), dir / entry.path().filename());
    CHECK(!generate_assets(dir).regenerated);
    fs::remove(dir / "studio.png");
    CHECK(generate_assets(dir).regenerated);
    CHECK(fs::exists(dir / "studio.png"));
    write_file_atomically(dir / kStampName, "rsl-assets 0\n");
    CHECK(generate_assets(dir).regenerated);
    CHECK(!generate_assets(dir).regenerated);
}

TEST_CASE("glb files round-trip the generated models exactly", "[assets]") {
    for (const auto& [file, model] : {std::pair{"robot.glb", &robot()}, std::pair{"kitchen.glb", &kitchen()}}) {
        INFO(file);
        const Scene loaded = load_scene(tree().generated / file);
        const Scene& s = model->scene;
        REQUIRE(loaded.parts.size() == s.parts.size());
        for (size_t p = 0; p < s.parts.size(); ++p) {
            const TriangleMesh &a = loaded.parts[p].mesh, &b = s.parts[p].mesh;
            CHECK(loaded.parts[p].name == s.parts[p].name);
            REQUIRE(a.vertex_count() == b.vertex_count());
            CHECK((a.indices == b.indices));
            CHECK((a.positions == b.positions));
            // Analytic normals and tangents survive (the loader only renormalizes them).
            float normal_error = 0, tangent_error = 0;
            for (size_t v = 0; v < a.vertex_count(); ++v) {
                normal_error = std::max(normal_error, glm::distance(a.normals[v], b.normals[v]));
                tangent_error = std::max(tangent_error, glm::distance(a.tangents[v], b.tangents[v]));
            }
            CHECK(normal_error < 1e-6f);
            CHECK(tangent_error < 1e-6f);
            for (float t : {0.0f, 0.37f, 1.1f, model->loop_seconds})
                CHECK(max_matrix_difference(loaded.part_transform_at(int(p), t), s.part_transform_at(int(p), t)) < 1e-6f);
        }
    }
    const Scene ground = load_scene(tree().generated / "ground.obj");
    REQUIRE(ground.parts.size() == 1);
    CHECK(ground.parts[0].mesh.vertex_count() == make_ground().vertex_count());
}

TEST_CASE("scene files load with their generated assets", "[assets]") {
    const GeneratedTree& t = tree();
    for (const char* name : {"default.json", "robot.json"}) {
        INFO(name);
        const Scene s = load_scene(t.scenes / name);
        CHECK(s.parts.size() == 13);  // 12 robot parts + the ground
        CHECK(s.materials[part_named(s, "torso").material].name == "steel");
        CHECK(s.materials[part_named(s, "ground").material].name == "floor");
        CHECK(s.environment.file.filename() == "sunsky.exr");
        CHECK(s.animation.end - s.animation.start == Approx(kRobotWalkSeconds));
    }
    const Scene k = load_scene(t.scenes / "kitchen.json");
    CHECK(k.parts.size() == 5);
    CHECK(k.environment.second_file.filename() == "overcast.exr");
    REQUIRE(k.lights.size() == 1);
    CHECK(glm::distance(k.lights[0].position_at(k, 0), k.lights[0].position_at(k, 2)) > 0.5f);  // the light moves
    CHECK(k.animation.end == Approx(kKitchenLoopSeconds));

    if (!fs::exists(RSL_SHARED_ASSETS)) {
        WARN("SKIPPED: bunny.json needs " << RSL_SHARED_ASSETS);
        return;
    }
    // The benchmark scene that needs data from outside the repository (assets/README.md).
    const Scene b = load_scene(fs::path(RSL_SOURCE_DIR) / "assets/external/bunny.json");
    CHECK(b.parts.size() == 2);
    CHECK(b.environment.file.filename() == "grace.hdr");
}
