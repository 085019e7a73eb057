// The binned-SAH builder of the GPU's BVH (src/rays/bvh_builder.h): every
// primitive in exactly one leaf, every box holding what lies below it.
#include <catch2/catch.hpp>

#include <random>

#include "src/rays/bvh_builder.h"
#include "tests/trace/trace_test_scenes.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

bool contains(const Bounds& outer, const Bounds& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

// Walks the tree: each child's box holds its primitives' boxes (leaves) or
// its node's two boxes; returns the primitives seen, counting repeats.
void check_tree(const BvhTree& tree, const std::vector<Bounds>& boxes, int max_depth) {
    std::vector<int> seen(boxes.size(), 0);
    struct Entry {
        int node, depth;
    };
    std::vector<Entry> stack{{0, 1}};
    while (!stack.empty()) {
        const Entry e = stack.back();
        stack.pop_back();
        REQUIRE(e.node < int(tree.nodes.size()));
        CHECK(e.depth <= max_depth + 1);
        for (const BvhChild& c : tree.nodes[size_t(e.node)].child) {
            if (c.count > 0) {
                for (int i = c.index; i < c.index + c.count; ++i) {
                    const int primitive = tree.order[size_t(i)];
                    ++seen[size_t(primitive)];
                    CHECK(contains(c.box, boxes[size_t(primitive)]));
                }
            } else if (!c.box.empty()) {
                for (const BvhChild& below : tree.nodes[size_t(c.index)].child)
                    if (!below.box.empty()) CHECK(contains(c.box, below.box));
                stack.push_back({c.index, e.depth + 1});
            }
        }
    }
    for (size_t i = 0; i < seen.size(); ++i) {
        INFO("primitive " << i);
        CHECK(seen[i] == 1);
    }
}

TEST_CASE("BVH: every triangle in one leaf, every box holds its children", "[rays][bvh]") {
    for (const TriangleMesh& mesh : {test::make_icosphere(1.0f, 4), test::make_plane(2.0f, 40),
                                     test::make_flat_box(Vec3(0.3f, 1.0f, 0.1f), 6)}) {
        const std::vector<Bounds> boxes = triangle_boxes(mesh);
        const BvhTree tree = build_bvh(boxes);
        INFO(mesh.name << ": " << boxes.size() << " triangles, " << tree.nodes.size() << " nodes, depth " << tree.depth);
        check_tree(tree, boxes, BvhBuildOptions{}.max_depth);
        CHECK(tree.nodes.size() < boxes.size());  // leaves of several triangles
    }
}

TEST_CASE("BVH: random boxes, coincident boxes, the depth limit, one box and none", "[rays][bvh]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<Bounds> boxes;
    for (int i = 0; i < 3000; ++i) {
        Bounds b;
        const Vec3 c = test::random_vec3(unit, rng);
        const Vec3 size = glm::abs(test::random_vec3(unit, rng));
        b.extend(c), b.extend(c + 0.05f * size);
        boxes.push_back(b);
    }
    check_tree(build_bvh(boxes), boxes, BvhBuildOptions{}.max_depth);
    // Every box the same: no split by position; halves until the leaves are small.
    const std::vector<Bounds> same(100, boxes.front());
    const BvhTree coincident = build_bvh(same);
    check_tree(coincident, same, BvhBuildOptions{}.max_depth);
    CHECK(coincident.depth <= 8);
    // A depth limit forces larger leaves, never a deeper tree.
    BvhBuildOptions shallow;
    shallow.max_depth = 3;
    const BvhTree limited = build_bvh(boxes, shallow);
    check_tree(limited, boxes, 3);
    CHECK(limited.depth <= 4);
    const BvhTree one = build_bvh({boxes.front()});
    REQUIRE(one.nodes.size() == 1);
    CHECK(one.nodes[0].child[0].count == 1);
    CHECK(one.nodes[0].child[1].box.empty());
    const BvhTree none = build_bvh({});
    REQUIRE(none.nodes.size() == 1);
    CHECK(none.nodes[0].child[0].count == 0);
    CHECK(none.nodes[0].child[0].box.empty());
}

}  // namespace
}  // namespace rsl
