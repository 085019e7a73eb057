#include "src/render/vertex_blocks.h"

#include <algorithm>
#include <numeric>

#include "src/core/error.h"
#include "src/core/mesh.h"

namespace rsl {

namespace {

void split_cell(std::span<const Vec3> positions, std::span<int> cell, int block_size) {
    const size_t n = cell.size();
    if (n <= size_t(block_size)) return;
    Bounds box;
    for (int v : cell) box.extend(positions[size_t(v)]);
    const Vec3 extent = box.hi - box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    // The lower half holds whole blocks: half the cell's blocks, rounded up.
    const size_t blocks = (n + size_t(block_size) - 1) / size_t(block_size);
    const size_t lower = (blocks + 1) / 2 * size_t(block_size);
    // Ties broken by index, so that the order does not depend on the sort's.
    auto before = [&](int a, int b) {
        const float pa = positions[size_t(a)][axis], pb = positions[size_t(b)][axis];
        return pa < pb || (pa == pb && a < b);
    };
    std::nth_element(cell.begin(), cell.begin() + std::ptrdiff_t(lower), cell.end(), before);
    split_cell(positions, cell.first(lower), block_size);
    split_cell(positions, cell.subspan(lower), block_size);
}

}  // namespace

std::vector<int> spatial_block_order(std::span<const Vec3> positions, int block_size) {
    RSL_CHECK(block_size > 0);
    std::vector<int> order(positions.size());
    std::iota(order.begin(), order.end(), 0);
    split_cell(positions, order, block_size);
    return order;
}

std::vector<VertexBlock> vertex_blocks(const std::vector<std::vector<int>>& orders) {
    std::vector<VertexBlock> blocks;
    for (size_t p = 0; p < orders.size(); ++p) {
        const int n = int(orders[p].size());
        for (int begin = 0; begin < n; begin += kShadeBlock)
            blocks.push_back(VertexBlock{int(p), begin, std::min(n, begin + kShadeBlock)});
    }
    return blocks;
}

}  // namespace rsl
