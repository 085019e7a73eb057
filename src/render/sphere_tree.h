#pragma once
// A bounding-volume hierarchy over spheres, rebuilt every frame: which of
// the spheres overlap a query sphere, in O(log n + hits) instead of O(n).
// The occluder culling (culling.h) puts every occluder's field reach in it
// and asks, per receiver, which reaches the receiver lies in, so a frame's
// cost follows the pairs that can interact, not parts².
#include <cstdint>
#include <span>
#include <vector>

#include "src/core/mesh.h"

namespace rsl {

class SphereTree {
public:
    // Rebuilds over `spheres` (ids are their indices); reusing one tree
    // across frames of the same size does not allocate.
    void build(std::span<const BoundingSphere> spheres);

    // Appends to `out`, in ascending id order, the ids of the spheres that
    // meet `query` (centre distance ≤ sum of radii, with a relative margin of
    // 1e-5 so that a caller's exact test decides the ties). Thread-safe.
    void overlapping(const BoundingSphere& query, std::vector<int>& out) const;

    size_t size() const { return spheres_.size(); }

private:
    struct Node {
        Bounds box;        // of the spheres below
        int begin, count;           // the ids_[begin .. begin + count) below
        int left = -1, right = -1;  // children; −1 for a leaf
    };
    int build_node(int begin, int count);

    std::vector<BoundingSphere> spheres_;
    std::vector<int> ids_;
    std::vector<Node> nodes_;
};

}  // namespace rsl
