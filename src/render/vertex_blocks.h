#pragma once
// The order in which the CPU renderer shades a part's vertices, in blocks of
// `block_size` (kShadeBlock). Culling works per block (its bounding sphere
// against each occluder's reach and bounding cone), so a block must be small
// in space: the vertex order of a mesh is not. A generated ground lists its
// vertices row by row, so a block of 256 was two rows across the whole ground
// — a strip as long as the scene, within reach of nearly every part — and
// the ground took 89% of the yard-128's per-vertex culling work for 15% of
// its vertices.
#include <span>
#include <vector>

#include "src/core/math.h"

namespace rsl {

// Vertices per block: the CPU renderer's unit of work and the GPU's workgroup.
inline constexpr int kShadeBlock = 256;

// One block: a range [begin, end) of its part's spatial_block_order.
struct VertexBlock {
    int part;
    int begin, end;
};
// The blocks of parts whose spatial_block_order is `orders` (one per part), part by part.
std::vector<VertexBlock> vertex_blocks(const std::vector<std::vector<int>>& orders);

// A permutation of the vertex indices whose consecutive runs of block_size
// (the last one shorter) are compact in space: the points split recursively
// at a multiple of block_size along the longest side of their bounds, so each
// block is one cell of a k-d tree. Deterministic.
std::vector<int> spatial_block_order(std::span<const Vec3> positions, int block_size);

}  // namespace rsl
