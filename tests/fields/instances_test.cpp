// Fields per unique (mesh, parameters): parts that share a mesh are grouped
// by content, each unique field is baked and stored once (its file is what a
// bake of that mesh alone writes), and shards of a bake split the unique
// fields into disjoint sets whose union is the full bake, byte for byte.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>

#include "src/fields/field_cache.h"
#include "src/fields/field_file.h"
#include "src/formats/scene_file.h"
#include "tests/test_support.h"
#include "tests/trace/trace_test_scenes.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

// Low settings: every bake of these meshes takes milliseconds.
void tiny_settings(Scene& scene) {
    PrecomputeSettings& pre = scene.precompute;
    pre.svdf_resolution = 8, pre.svdf_clusters = 4, pre.svdf_vectors = 2, pre.svdf_supersampling = 1;
    pre.ovdf_shells = 2, pre.ovdf_cube_resolution = 4, pre.ovdf_vdt_resolution = 8, pre.ovdf_vectors = 2;
}

Transform pose(float x, float z, float degrees, float scale) {
    Transform t;
    t.translation = Vec3(x, 0.3f, z);
    t.rotation = glm::angleAxis(glm::radians(degrees), glm::normalize(Vec3(0.2f, 1.0f, 0.1f)));
    t.scale = Vec3(scale);
    return t;
}

// `balls` instances of one icosphere and `plates` of one plane, interleaved,
// each with a name, transform and material of its own; optionally a third
// mesh (a finer icosphere) once.
Scene instanced_scene(const fs::path& source, int balls, int plates, bool third = false) {
    Scene scene = make_scene("instances");
    scene.materials.push_back(lambert(Color(0.3f), "dark"));
    scene.source = source;
    tiny_settings(scene);
    for (int i = 0; i < std::max(balls, plates); ++i) {
        if (i < balls) {
            const int p = add_part(scene, make_icosphere(0.3f, 1, fmt::format("ball{}", i)),
                                   pose(float(i), 0.0f, 20.0f * float(i), 1.0f + 0.25f * float(i % 3)), i % 2);
            scene.parts[size_t(p)].mesh.name = scene.parts[size_t(p)].name;  // as the glTF loader names them
        }
        if (i < plates) add_part(scene, make_plane(1.0f, 3, fmt::format("plate{}", i)), pose(float(i), 2.0f, 35.0f * float(i), 1.0f));
    }
    if (third) add_part(scene, make_icosphere(0.5f, 2, "big"), pose(0, -3, 0, 1));
    return scene;
}

std::vector<fs::path> rslf_files(const fs::path& dir) {
    std::vector<fs::path> files;
    if (fs::exists(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".rslf") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

FieldCacheOptions quiet_options(const Scene& scene, const fs::path& directory, FieldShard shard = {}) {
    FieldCacheOptions options = default_field_options(scene);
    options.directory = directory;
    options.shard = shard;
    return options;
}

// The files a run baked or read (its shard's share).
std::set<fs::path> touched(const SceneFields& fields) {
    std::set<fs::path> files;
    for (const UniqueFields& u : fields.unique)
        for (const FieldOutcome* o : {&u.svdf_outcome, &u.ovdf_outcome})
            if (o->state != FieldState::Skipped) files.insert(o->file);
    return files;
}

}  // namespace

TEST_CASE("group_instances: parts group by mesh content, not by name, material or transform", "[fields][instances]") {
    Scene scene = instanced_scene("groups.json", 5, 3);
    std::vector<MeshInstances> groups = group_instances(scene);
    REQUIRE(groups.size() == 2);
    // Interleaved: balls are parts 0, 2, 4, 6, 7; plates 1, 3, 5.
    CHECK(groups[0].parts == std::vector<int>{0, 2, 4, 6, 7});
    CHECK(groups[1].parts == std::vector<int>{1, 3, 5});
    CHECK(groups[0].mesh_hash == mesh_hash(scene.parts[0].mesh));
    CHECK(groups[0].mesh_hash != groups[1].mesh_hash);

    // Any change of what the fields depend on makes another mesh: a position,
    // a normal, a tangent (the SVDF's frames), the triangles.
    for (int change = 0; change < 4; ++change) {
        Scene changed = scene;
        TriangleMesh& mesh = changed.parts[4].mesh;
        if (change == 0) mesh.positions[3].x += 1e-6f;
        if (change == 1) mesh.normals[3] = glm::normalize(mesh.normals[3] + Vec3(1e-3f, 0, 0));
        if (change == 2) mesh.tangents[3].w = -mesh.tangents[3].w;
        if (change == 3) std::swap(mesh.indices[0], mesh.indices[1]);
        INFO("change " << change);
        groups = group_instances(changed);
        REQUIRE(groups.size() == 3);
        CHECK(groups[0].parts == std::vector<int>{0, 2, 6, 7});
        CHECK(groups[2].parts == std::vector<int>{4});
    }
}

TEST_CASE("Many instances of two meshes bake two fields of each kind, once", "[fields][instances]") {
    const fs::path dir = scratch_dir("instances_bake");
    const Scene scene = instanced_scene(dir / "many.json", 12, 7);
    const fs::path cache = dir / ".rsl-cache";
    const FieldCacheOptions options = quiet_options(scene, cache);

    const SceneFields fields = bake_or_load_fields(scene, options);
    REQUIRE(fields.unique.size() == 2);
    CHECK(fields.count(FieldState::Baked) == 4);
    CHECK(fields.count(FieldState::Reused) == 0);
    const std::vector<fs::path> files = rslf_files(cache);
    REQUIRE(files.size() == 4);  // not 19 × 2
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const UniqueFields& u = fields.unique[size_t(fields.unique_of_part[p])];
        CHECK(std::count(u.mesh.parts.begin(), u.mesh.parts.end(), int(p)) == 1);
        CHECK(u.mesh.mesh_hash == mesh_hash(scene.parts[p].mesh));
    }
    CHECK(fields.unique[0].mesh.parts.size() == 12);
    CHECK(fields.unique[1].mesh.parts.size() == 7);
    for (const UniqueFields& u : fields.unique) {
        REQUIRE(u.svdf);
        REQUIRE(u.ovdf);
        CHECK(u.svdf_outcome.disk_bytes == fs::file_size(u.svdf_outcome.file));
        CHECK(u.svdf_outcome.memory_bytes == memory_bytes(*u.svdf));
        CHECK(u.svdf_outcome.memory_bytes >= u.svdf->model.tables.size() * sizeof(float));
        // The file names carry no scene or part: only the kind and the key.
        CHECK(u.svdf_outcome.file.filename().string().rfind("svdf-", 0) == 0);
        CHECK(u.ovdf_outcome.file.filename().string().rfind("ovdf-", 0) == 0);
    }

    // Each shared file holds exactly what baking that mesh alone (as a
    // one-part-per-file cache did) writes: the bake is deterministic.
    const fs::path alone = dir / "alone";
    fs::create_directories(alone);
    for (const UniqueFields& u : fields.unique) {
        const TriangleMesh& mesh = scene.parts[size_t(u.mesh.parts.back())].mesh;  // any instance's mesh
        write_svdf(alone / "s.rslf", bake_svdf(mesh, options.svdf), mesh_hash(mesh));
        write_ovdf(alone / "o.rslf", bake_ovdf(mesh, options.ovdf), mesh_hash(mesh));
        CHECK(read_bytes(alone / "s.rslf") == read_bytes(u.svdf_outcome.file));
        CHECK(read_bytes(alone / "o.rslf") == read_bytes(u.ovdf_outcome.file));
    }

    // A second run reads the four files and bakes nothing; another scene that
    // uses one of the meshes (in other parts, other poses) finds its files.
    const SceneFields again = bake_or_load_fields(scene, options);
    CHECK(again.count(FieldState::Reused) == 4);
    CHECK(again.count(FieldState::Baked) == 0);
    const Scene other = instanced_scene(dir / "other.json", 0, 3, true);  // plates and a new mesh
    const SceneFields shared = bake_or_load_fields(other, quiet_options(other, cache));
    CHECK(shared.count(FieldState::Reused) == 2);  // the plate's
    CHECK(shared.count(FieldState::Baked) == 2);   // the big ball's
    CHECK(rslf_files(cache).size() == 6);
}

TEST_CASE("Caches of the per-part naming are left alone, never read", "[fields][instances]") {
    const fs::path dir = scratch_dir("instances_old_cache");
    const Scene scene = instanced_scene(dir / "old.json", 2, 1);
    const fs::path cache = dir / ".rsl-cache";
    fs::create_directories(cache);
    // What the per-part cache named its files: <scene>.<part>-<name>.<kind>.<key>.rslf.
    const fs::path old = cache / "old.0-ball0.svdf.0123456789abcdef.rslf";
    write_text(old, "not a field file");
    WarningCapture warnings;
    const SceneFields fields = bake_or_load_fields(scene, quiet_options(scene, cache));
    CHECK(fields.count(FieldState::Baked) == 4);
    CHECK(warnings.messages().empty());
    CHECK(read_bytes(old) == "not a field file");
    CHECK(rslf_files(cache).size() == 5);
}

TEST_CASE("Shards 0/2 and 1/2 bake disjoint sets whose union is the full bake, byte for byte", "[fields][instances][shard]") {
    const fs::path dir = scratch_dir("instances_shards");
    const Scene scene = instanced_scene(dir / "sharded.json", 4, 3, true);  // 3 unique meshes: 6 files
    const fs::path shared = dir / "shared", full = dir / "full";

    const SceneFields first = bake_or_load_fields(scene, quiet_options(scene, shared, {0, 2}));
    const std::set<fs::path> first_files = touched(first);
    CHECK(first.count(FieldState::Baked) == 3);
    CHECK(rslf_files(shared).size() == 3);
    const SceneFields second = bake_or_load_fields(scene, quiet_options(scene, shared, {1, 2}));
    const std::set<fs::path> second_files = touched(second);
    CHECK(second.count(FieldState::Baked) == 3);
    CHECK(second.count(FieldState::Reused) == 0);  // nothing of shard 0's was read again
    for (const fs::path& f : first_files) CHECK(second_files.count(f) == 0);

    const SceneFields whole = bake_or_load_fields(scene, quiet_options(scene, full));
    CHECK(whole.count(FieldState::Baked) == 6);
    const std::vector<fs::path> union_files = rslf_files(shared), full_files = rslf_files(full);
    REQUIRE(union_files.size() == 6);
    REQUIRE(full_files.size() == 6);
    for (size_t i = 0; i < 6; ++i) {
        INFO(union_files[i]);
        CHECK(union_files[i].filename() == full_files[i].filename());
        CHECK(read_bytes(union_files[i]) == read_bytes(full_files[i]));
        CHECK((first_files.count(union_files[i]) + second_files.count(union_files[i])) == 1);
    }
    // A full run on the shards' folder then bakes nothing.
    const SceneFields after = bake_or_load_fields(scene, quiet_options(scene, shared));
    CHECK(after.count(FieldState::Baked) == 0);
    CHECK(after.count(FieldState::Reused) == 6);

    // Any N: every file is exactly one shard's, shares differ by at most one,
    // and the split does not depend on the parts' order.
    Scene reversed = scene;
    std::reverse(reversed.parts.begin(), reversed.parts.end());
    for (int n : {1, 2, 3, 4, 5, 6, 7, 11}) {
        std::map<fs::path, int> owner;
        std::vector<int> share(size_t(n), 0);
        for (int i = 0; i < n; ++i)
            for (const Scene* s : {&scene, static_cast<const Scene*>(&reversed)}) {
                const SceneFields plan = plan_fields(*s, quiet_options(*s, shared, {i, n}));
                for (const UniqueFields& u : plan.unique)
                    for (const FieldOutcome* o : {&u.svdf_outcome, &u.ovdf_outcome}) {
                        CHECK(o->state == FieldState::Skipped);  // a plan reads and bakes nothing
                        if (!o->wanted) continue;
                        const auto [it, inserted] = owner.emplace(o->file, i);
                        CHECK(it->second == i);
                        if (s == &scene) ++share[size_t(i)];
                    }
            }
        INFO("N = " << n);
        CHECK(owner.size() == 6);
        CHECK(*std::max_element(share.begin(), share.end()) - *std::min_element(share.begin(), share.end()) <= 1);
    }
}

TEST_CASE("parse_field_shard: I/N with 0 <= I < N, else an error naming the option and the text", "[fields][shard][bad-input]") {
    CHECK(parse_field_shard("0/1").all());
    const FieldShard s = parse_field_shard("3/8");
    CHECK(s.index == 3);
    CHECK(s.count == 8);
    CHECK(parse_field_shard("0/2").index == 0);
    for (const char* bad : {"2/2", "5/3", "-1/2", "1/0", "0/0", "1/-2", "a/2", "1/b", "1", "1/", "/2", "", "1/2/3",
                            " 1/2", "1/2 ", "1.0/2", "99999999999/2"}) {
        INFO(bad);
        const std::string message = error_of([&] { parse_field_shard(bad); });
        CHECK(message.find(fmt::format("--shard '{}'", bad)) != std::string::npos);
        CHECK(message.find("expected I/N") != std::string::npos);
    }
}

TEST_CASE("assets/scenes/instanced.json: 17 parts of 3 unique meshes", "[fields][instances]") {
    const Scene scene = load_scene(fs::path(RSL_SOURCE_DIR) / "assets/scenes/instanced.json");
    REQUIRE(scene.parts.size() == 17);
    const std::vector<MeshInstances> groups = group_instances(scene);
    REQUIRE(groups.size() == 3);  // the ground, the orb, the teapot
    CHECK(groups[0].parts.size() == 1);
    CHECK(groups[1].parts.size() == 8);
    CHECK(groups[2].parts.size() == 8);
    // Every instance has a pose of its own.
    std::set<std::pair<float, float>> origins;
    for (int p : groups[1].parts) origins.emplace(scene.part_transform_at(p, 0)[3].x, scene.part_transform_at(p, 0)[3].z);
    CHECK(origins.size() == 8);
}

TEST_CASE("A different subdivision setting selects other field files, never a stale one", "[fields][instances][subdivide]") {
    const fs::path dir = scratch_dir("subdivision_cache");
    write_text(dir / "box.obj", kUnitBoxObj);
    write_text(dir / "none.hdr", "");
    auto planned_files = [&](const std::string& setting) {
        write_text(dir / "scene.json", R"({"parts": [{"obj": "box.obj"}, {"obj": "box.obj", "name": "again"}],
                                           "environment": {"file": "none.hdr"}, "subdivision": )" + setting + "}");
        Scene scene = load_scene(dir / "scene.json");
        tiny_settings(scene);
        const SceneFields plan = plan_fields(scene, default_field_options(scene));
        REQUIRE(plan.unique.size() == 1);  // the two instances still share their subdivided mesh
        return std::pair{plan.unique[0].svdf_outcome.file, plan.unique[0].ovdf_outcome.file};
    };
    const auto off = planned_files("false"), coarse = planned_files(R"({"edge": 0.4})"),
               fine = planned_files(R"({"edge": 0.2})");
    CHECK(off.first != coarse.first);
    CHECK(off.second != coarse.second);
    CHECK(coarse.first != fine.first);
    CHECK(coarse.second != fine.second);
    CHECK(planned_files(R"({"edge": 0.2})") == fine);  // and the same setting finds its files again
}
