// The CPU renderer's block order (vertex_blocks.h): a permutation whose
// blocks are compact in space, where a mesh's own order need not be.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "src/core/mesh.h"
#include "src/render/block_scratch.h"
#include "src/render/vertex_blocks.h"
#include "tests/random_cases.h"

namespace rsl {
namespace {

// The largest side of the bounds of each run of `block` points in `order`.
std::vector<float> block_sides(const std::vector<Vec3>& points, const std::vector<int>& order, int block) {
    std::vector<float> sides;
    for (size_t begin = 0; begin < order.size(); begin += size_t(block)) {
        Bounds box;
        for (size_t i = begin; i < std::min(order.size(), begin + size_t(block)); ++i)
            box.extend(points[size_t(order[i])]);
        const Vec3 extent = box.hi - box.lo;
        sides.push_back(std::max({extent.x, extent.y, extent.z}));
    }
    return sides;
}

TEST_CASE("the block order is a deterministic permutation", "[render][culling]") {
    std::mt19937 rng{11};
    std::uniform_real_distribution<float> u(-1, 1);
    for (const int count : {0, 1, 255, 256, 257, 1000, 5000}) {
        for (const int block : {1, 7, 256}) {
            std::vector<Vec3> points(static_cast<size_t>(count));
            for (Vec3& p : points) p = test::random_vec3(u, rng) * Vec3(1, 1, 0.1f);
            if (count > 10) points[3] = points[5] = points[9];  // ties
            const std::vector<int> order = spatial_block_order(points, block);
            std::vector<int> sorted = order;
            std::sort(sorted.begin(), sorted.end());
            for (int i = 0; i < count; ++i) REQUIRE(sorted[size_t(i)] == i);
            REQUIRE(spatial_block_order(points, block) == order);
        }
    }
}

TEST_CASE("a ground's blocks are square patches, not rows across it", "[render][culling]") {
    // A 121 × 121 grid, row by row as a generated ground lists it: runs of 256
    // in that order are two rows across the whole ground.
    const int side = 121;
    std::vector<Vec3> points;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) points.push_back(Vec3(float(i), 0.0f, float(j)));
    std::vector<int> mesh_order(points.size());
    for (size_t i = 0; i < points.size(); ++i) mesh_order[i] = int(i);
    const std::vector<float> rows = block_sides(points, mesh_order, kShadeBlock);
    REQUIRE(*std::max_element(rows.begin(), rows.end()) == float(side - 1));

    // A 16 × 16 patch has side 15; the k-d cells of 256 points over a 121-wide
    // grid are near-square, within 2× of that.
    const std::vector<float> blocks = block_sides(points, spatial_block_order(points, kShadeBlock), kShadeBlock);
    CAPTURE(*std::max_element(blocks.begin(), blocks.end()));
    CHECK(*std::max_element(blocks.begin(), blocks.end()) <= 32.0f);
}

}  // namespace
}  // namespace rsl
