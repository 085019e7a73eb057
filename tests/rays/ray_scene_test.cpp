// RayScene against a brute-force ray-triangle intersector in double precision.
#include <random>

#include <catch2/catch.hpp>

#include "src/core/error.h"
#include "src/rays/ray_scene.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

using namespace rsl;

namespace {

struct BruteHit {
    double t = 1e300;
    int instance = -1, triangle = -1;
    double u = 0, v = 0;
    DVec3 normal{0};
};

// Möller–Trumbore over every triangle of every instance, in world space.
BruteHit brute_force(const std::vector<TriangleMesh>& meshes, const std::vector<Mat4>& transforms, DVec3 o,
                     DVec3 d) {
    BruteHit best;
    for (size_t inst = 0; inst < meshes.size(); ++inst) {
        const TriangleMesh& m = meshes[inst];
        const glm::dmat4 x(transforms[inst]);
        for (size_t t = 0; t < m.triangle_count(); ++t) {
            DVec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = DVec3(x * glm::dvec4(DVec3(m.positions[m.indices[3 * t + k]]), 1.0));
            const DVec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
            const DVec3 q = glm::cross(d, e2);
            const double det = glm::dot(e1, q);
            if (std::abs(det) < 1e-300) continue;
            const DVec3 s = o - p[0];
            const double u = glm::dot(s, q) / det;
            const DVec3 r = glm::cross(s, e1);
            const double v = glm::dot(d, r) / det;
            const double dist = glm::dot(e2, r) / det;
            if (u < 0 || v < 0 || u + v > 1 || dist <= 0 || dist >= best.t) continue;
            best = {dist, int(inst), int(t), u, v, glm::normalize(glm::cross(e1, e2))};
        }
    }
    return best;
}

Mat4 random_pose(std::mt19937& rng) {
    std::uniform_real_distribution<float> uni(-1, 1);
    const Vec3 axis = glm::normalize(test::random_vec3(uni, rng) + Vec3(0, 0, 1e-3f));
    Transform tr;
    tr.translation = 1.5f * test::random_vec3(uni, rng);
    tr.rotation = glm::angleAxis(3.0f * uni(rng), axis);
    tr.scale = Vec3(0.6f + 0.3f * uni(rng));
    return tr.matrix();
}

}  // namespace

TEST_CASE("RayScene hits agree with a brute-force intersector over random instanced poses", "[trace][ray_scene]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(-1, 1);
    const std::vector<TriangleMesh> meshes = {test::make_icosphere(0.7f, 2), test::make_plane(2.0f, 6),
                                              test::make_icosphere(0.4f, 1)};
    std::vector<Mat4> poses;
    RayScene scene;
    for (const auto& mesh : meshes) {
        poses.push_back(random_pose(rng));
        scene.add_instance(scene.add_mesh(mesh), poses.back());
    }
    scene.commit();
    REQUIRE(scene.instance_count() == 3);
    REQUIRE(scene.world_diagonal() > 1.0f);

    int hits = 0;
    for (int trial = 0; trial < 1500; ++trial) {
        const Vec3 o = 4.0f * test::random_vec3(uni, rng);
        const Vec3 target = 1.2f * test::random_vec3(uni, rng);
        const Vec3 d = glm::normalize(target - o);
        const RayHit hit = scene.intersect(o, d);
        const BruteHit ref = brute_force(meshes, poses, DVec3(o), DVec3(d));
        const bool ref_hit = ref.instance >= 0;
        // Rays grazing a triangle edge may legitimately go either way; the
        // positions must still agree.
        REQUIRE(hit.hit == ref_hit);
        REQUIRE(scene.occluded(o, d, 0.0f, 1e30f) == ref_hit);
        if (!ref_hit) continue;
        ++hits;
        REQUIRE(hit.t == Approx(ref.t).epsilon(1e-4));
        if (hit.instance == ref.instance && hit.triangle == ref.triangle) {
            REQUIRE(hit.u == Approx(ref.u).margin(1e-4));
            REQUIRE(hit.v == Approx(ref.v).margin(1e-4));
            REQUIRE(glm::dot(DVec3(hit.geometric_normal), ref.normal) == Approx(1.0).margin(1e-4));
        }
        // The ray stops just before the hit: unoccluded; just after: occluded.
        REQUIRE_FALSE(scene.occluded(o, d, 0.0f, hit.t * 0.999f));
        REQUIRE(scene.occluded(o, d, 0.0f, hit.t * 1.001f));
    }
    REQUIRE(hits > 100);
}

TEST_CASE("occluded_batch equals single-ray queries, for shared and per-ray t_far", "[trace][ray_scene]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-1, 1);
    RayScene scene;
    scene.add_instance(scene.add_mesh(test::make_icosphere(0.5f, 3)), Mat4(1.0f));
    scene.add_instance(scene.add_mesh(test::make_plane(3.0f, 4)), glm::translate(Mat4(1.0f), Vec3(0, -0.6f, 0)));
    scene.commit();
    for (int trial = 0; trial < 20; ++trial) {
        const Vec3 origin = 2.0f * test::random_vec3(uni, rng) + Vec3(0, 1.5f, 0);
        const int count = 1 + trial * 7;  // partial packets too
        std::vector<Vec3> dirs(count);
        std::vector<float> t_fars(count);
        for (int k = 0; k < count; ++k) {
            dirs[k] = glm::normalize(test::random_vec3(uni, rng) - 0.3f * origin);
            t_fars[k] = 0.5f + 3.0f * (uni(rng) + 1.0f);
        }
        std::vector<uint8_t> shared(count), each(count);
        scene.occluded_batch(origin, dirs.data(), count, 0.0f, 1e30f, shared.data());
        scene.occluded_batch(origin, dirs.data(), t_fars.data(), count, 0.0f, each.data());
        for (int k = 0; k < count; ++k) {
            REQUIRE(bool(shared[k]) == !scene.occluded(origin, dirs[k], 0.0f, 1e30f));
            REQUIRE(bool(each[k]) == !scene.occluded(origin, dirs[k], 0.0f, t_fars[k]));
        }
    }
}

TEST_CASE("intersect_packet gives intersect()'s hit for every ray, coherent or not, full or partial", "[trace][ray_scene]") {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> uni(-1, 1);
    RayScene scene;
    scene.add_instance(scene.add_mesh(test::make_icosphere(0.5f, 3)), random_pose(rng));
    scene.add_instance(scene.add_mesh(test::make_icosphere(0.3f, 2)), random_pose(rng));
    scene.add_instance(scene.add_mesh(test::make_plane(3.0f, 5)), glm::translate(Mat4(1.0f), Vec3(0, -0.8f, 0)));
    scene.commit();
    constexpr int kPacket = RayScene::kPrimaryPacket;
    int hits = 0, misses = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Vec3 origin = 3.0f * test::random_vec3(uni, rng) + Vec3(0, 1.0f, 0);
        const int count = 1 + trial % kPacket;
        // Half the packets are narrow cones (a camera's neighbouring pixels),
        // half point anywhere (every octant, many misses).
        const bool coherent = trial % 2 == 0;
        const Vec3 axis = glm::normalize(0.5f * test::random_vec3(uni, rng) - origin);
        float dx[kPacket], dy[kPacket], dz[kPacket];
        for (int k = 0; k < count; ++k) {
            const Vec3 d = coherent ? glm::normalize(axis + 0.05f * test::random_vec3(uni, rng))
                                    : glm::normalize(test::random_vec3(uni, rng) + Vec3(0, 0, 1e-3f));
            dx[k] = d.x, dy[k] = d.y, dz[k] = d.z;
        }
        RayHit packet[kPacket], bare[kPacket];
        scene.intersect_packet(origin, dx, dy, dz, count, packet);
        scene.intersect_packet(origin, dx, dy, dz, count, bare, false);
        for (int k = 0; k < count; ++k) {
            const RayHit single = scene.intersect(origin, Vec3(dx[k], dy[k], dz[k]));
            REQUIRE(packet[k].hit == single.hit);
            REQUIRE(bare[k].hit == single.hit);
            if (!single.hit) {
                ++misses;
                continue;
            }
            ++hits;
            for (const RayHit* h : {&packet[k], &bare[k]}) {
                REQUIRE(h->instance == single.instance);
                REQUIRE(h->triangle == single.triangle);
                REQUIRE(h->t == Approx(single.t).epsilon(1e-5));
                REQUIRE(h->u == Approx(single.u).margin(1e-5));
                REQUIRE(h->v == Approx(single.v).margin(1e-5));
            }
            REQUIRE(glm::length(packet[k].geometric_normal - single.geometric_normal) < 1e-5f);
            REQUIRE(bare[k].geometric_normal == Vec3(0));
        }
    }
    REQUIRE(hits > 500);
    REQUIRE(misses > 500);
}

TEST_CASE("Moving an instance changes queries after commit without rebuilding", "[trace][ray_scene]") {
    RayScene scene;
    const int mesh = scene.add_mesh(test::make_icosphere(0.5f, 2));
    const int id = scene.add_instance(mesh, Mat4(1.0f));
    scene.commit();
    const Vec3 origin(0, -3, 0), up(0, 1, 0);
    REQUIRE(scene.occluded(origin, up, 0.0f, 10.0f));
    scene.set_transform(id, glm::translate(Mat4(1.0f), Vec3(2, 0, 0)));
    REQUIRE_THROWS_AS(scene.occluded(origin, up, 0.0f, 10.0f), Error);  // not committed yet
    scene.commit();
    REQUIRE_FALSE(scene.occluded(origin, up, 0.0f, 10.0f));
    REQUIRE(scene.occluded(Vec3(2, -3, 0), up, 0.0f, 10.0f));
    const RayHit hit = scene.intersect(Vec3(2, -3, 0), up);
    REQUIRE(hit.hit);
    REQUIRE(hit.instance == id);
    REQUIRE(hit.t == Approx(2.5f).epsilon(0.01));
    REQUIRE(hit.geometric_normal.y < -0.9f);  // outward at the bottom of the sphere
}

TEST_CASE("Offset origins leave their own surface, also far from the origin", "[trace][ray_scene]") {
    for (float shift : {0.0f, 1e3f, 1e5f}) {
        const float scale = 1.0f + shift * 1e-3f;
        RayScene scene;
        const Mat4 pose = glm::translate(Mat4(1.0f), Vec3(shift, shift, -shift)) * glm::scale(Mat4(1.0f), Vec3(scale));
        scene.add_instance(scene.add_mesh(test::make_plane(2.0f, 8)), pose);
        scene.commit();
        RayOffset offset{scene.world_diagonal()};
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> uni(0, 1);
        int leaked = 0;
        for (int k = 0; k < 2000; ++k) {
            // Points on the plane (vertices and interiors), rays up to 0.01° above the horizon.
            const Vec2 local_xz = 2.0f * test::random_vec2(uni, rng) - 1.0f;
            const Vec3 local(local_xz.x, 0.0f, local_xz.y);
            const Vec3 p = Vec3(pose * Vec4(k % 2 ? glm::round(local * 4.0f) / 4.0f : local, 1.0f));
            const float elevation_draw = uni(rng);
            const float elevation = glm::radians(0.01f + 89.0f * elevation_draw * uni(rng));
            const float phi = 6.2831853f * uni(rng);
            const Vec3 d(std::cos(elevation) * std::cos(phi), std::sin(elevation), std::cos(elevation) * std::sin(phi));
            if (scene.occluded(offset.origin(p, Vec3(0, 1, 0)), d, 0.0f, 1e30f)) ++leaked;
            // And from below, rays going down are not stopped either.
            if (scene.occluded(offset.origin(p, Vec3(0, -1, 0)), -d, 0.0f, 1e30f)) ++leaked;
        }
        INFO("shift " << shift);
        REQUIRE(leaked == 0);
        // The offset is small against the scene: 1e-5 of it plus ~64 ULPs.
        REQUIRE(offset.distance(Vec3(shift)) < 1e-4f * scene.world_diagonal() + 1e-3f * shift * 1e-2f);
    }
}

TEST_CASE("A leaving hit is ignored within the hit part's own ray offsets, however large the scene", "[trace][ray_scene]") {
    // An origin a depth δ under the top face of a box, the ray straight up:
    // the ray leaves the box at t = δ. Within 4 of the box's ray offsets
    // (RayOffset of its own diagonal, about 8.5e-5 for the unit box) that hit
    // is ignored; deeper it blocks. A second box 1000 away makes the scene's
    // diagonal 1000: the answer must not change (with the scene's offset the
    // margin was 0.04, and the truth lit points 0.4 mm inside a part that its
    // SVDF, baked with the part alone, left dark). Scaling the box scales its margin.
    const TriangleMesh box = test::make_flat_box(Vec3(0.5f), 2, "box");
    for (const float scale : {1.0f, 10.0f}) {
        for (const bool far_box : {false, true}) {
            RayScene scene(/*origins_outside_surfaces=*/true);
            const int mesh = scene.add_mesh(box);
            scene.add_instance(mesh, glm::scale(Mat4(1.0f), Vec3(scale)));
            if (far_box) scene.add_instance(mesh, glm::translate(Mat4(1.0f), Vec3(1000.0f, 0.0f, 0.0f)));
            scene.commit();
            REQUIRE(scene.instance_diagonal(0) == Approx(scale * std::sqrt(3.0f)).epsilon(1e-5));
            const float top = 0.5f * scale;
            const float margin = 4.0f * RayOffset{scene.instance_diagonal(0)}.distance(Vec3(0.1f, top, 0.2f));
            for (const float depth : {0.5f * margin, 2.0f * margin}) {
                const Vec3 origin(0.1f, top - depth, 0.2f);
                const Vec3 up(0.0f, 1.0f, 0.0f);
                const bool expected = depth > margin;  // blocked
                INFO("scale " << scale << ", far box " << far_box << ", depth " << depth << ", margin " << margin);
                CHECK(scene.occluded(origin, up, 0.0f, 1e30f) == expected);
                uint8_t visible = 2;
                scene.occluded_batch(origin, &up, 1, 0.0f, 1e30f, &visible);
                CHECK(visible == (expected ? 0 : 1));
                scene.occluded_batch(&origin, &up, 1, 0.0f, 1e30f, &visible);
                CHECK(visible == (expected ? 0 : 1));
            }
        }
    }
}

TEST_CASE("Origins on another part's surface count as outside it: a ray that leaves is free, one that enters is blocked",
          "[trace][ray_scene]") {
    // A box under random rotations and non-uniform scales; origins on its
    // faces (where parts touch, a neighbour's vertex lies on them), rays in
    // random directions. The box is convex: a ray leaving a face never
    // meets it again, one entering always does.
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> uni(-1, 1);
    const TriangleMesh box = test::make_flat_box(Vec3(0.5f, 0.3f, 0.4f), 3, "box");
    int leaving = 0, entering = 0, wrong_with = 0, blocked_without = 0;
    for (int pose_index = 0; pose_index < 20; ++pose_index) {
        Transform tr;
        tr.translation = test::random_vec3(uni, rng);
        const float angle = 3.0f * uni(rng);
        tr.rotation = glm::angleAxis(angle, glm::normalize(test::random_vec3(uni, rng) + Vec3(1e-3f)));
        tr.scale = 1.0f + 0.5f * test::random_vec3(uni, rng);
        const Mat4 pose = tr.matrix();
        RayScene with(/*origins_outside_surfaces=*/true), without;
        for (RayScene* scene : {&with, &without}) {
            scene->add_instance(scene->add_mesh(box), pose);
            scene->commit();
        }
        const Mat3 normal_matrix = glm::transpose(glm::inverse(Mat3(pose)));
        for (int k = 0; k < 200; ++k) {
            // A point inside a random face: every third one on a vertex of
            // the face's 3×3 grid (±h/3), the others anywhere but its edges,
            // where a ray can enter one face and leave by the next.
            const int axis = int(3.0f * (0.5f + 0.5f * uni(rng))) % 3;
            const Vec3 half(0.5f, 0.3f, 0.4f);
            Vec3 local = 0.98f * half * test::random_vec3(uni, rng);
            if (k % 3 == 0)
                for (int c = 0; c < 3; ++c) local[c] = (uni(rng) < 0.0f ? -1.0f : 1.0f) * half[c] / 3.0f;
            const float side = uni(rng) < 0.0f ? -1.0f : 1.0f;
            local[axis] = side * half[axis];
            Vec3 outward_local(0);
            outward_local[axis] = side;
            const Vec3 origin = Vec3(pose * Vec4(local, 1.0f));
            const Vec3 outward = glm::normalize(normal_matrix * outward_local);
            const Vec3 dir = glm::normalize(test::random_vec3(uni, rng) + Vec3(1e-4f));
            const float cos_out = glm::dot(dir, outward);
            if (std::abs(cos_out) < 0.05f) continue;  // grazing: either answer is fair at an edge
            const bool blocked = with.occluded(origin, dir, 0.0f, 1e30f);
            INFO("pose " << pose_index << ", face axis " << axis << " side " << side << ", cos to outward " << cos_out
                          << ", local " << local.x << " " << local.y << " " << local.z << ", without "
                          << without.occluded(origin, dir, 0.0f, 1e30f));
            if (cos_out > 0.0f) {
                ++leaving;
                if (blocked) ++wrong_with;
                if (without.occluded(origin, dir, 0.0f, 1e30f)) ++blocked_without;
            } else {
                ++entering;
                CHECK(blocked);
            }
        }
    }
    CHECK(leaving > 1000);
    CHECK(entering > 1000);
    CHECK(wrong_with == 0);
    // Without the rule such origins are a coin toss: some leaving rays hit
    // the face they start on (the reason for the rule).
    CHECK(blocked_without > leaving / 20);
}
