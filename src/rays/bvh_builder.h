#pragma once
// A binary bounding volume hierarchy over boxes, built with binned SAH, in
// the flat layout the GPU traverses (src/gl/gpu_bvh.h,
// shaders/bvh_traverse.glsl): each node holds both children's boxes, so one
// node read tests two boxes. The GPU ray-traced baseline builds one per
// unique mesh (its triangles' boxes, in the mesh's frame) and one over the
// posed parts (docs/design/GPU_DESIGN.md "Ray-traced visibility").
#include <cstdint>
#include <vector>

#include "src/core/math.h"
#include "src/core/mesh.h"

namespace rsl {

// A node's child: a node (count = 0, index = the node) or a leaf (count
// primitives from index into BvhTree::order).
struct BvhChild {
    Bounds box;
    int index = 0, count = 0;
};
struct BvhNode {
    BvhChild child[2];
};

struct BvhTree {
    std::vector<BvhNode> nodes;  // nodes[0] is the root
    std::vector<int> order;      // primitive indices, leaf by leaf
    int depth = 0;               // nodes on the longest root-to-leaf path
};

struct BvhBuildOptions {
    int max_leaf = 4;    // primitives per leaf, unless the depth limit forces more
    int max_depth = 24;  // the traversal's stack bounds it (kBvhStack)
    int bins = 16;
};

// Binned SAH over the boxes' centroids (Wald 2007). An empty input gives a
// root whose children are empty (boxes that no ray enters); one box, a root
// with one leaf child and one empty child.
BvhTree build_bvh(const std::vector<Bounds>& boxes, const BvhBuildOptions& options = {});

// The boxes of a mesh's triangles, in its own frame.
std::vector<Bounds> triangle_boxes(const TriangleMesh& mesh);

}  // namespace rsl
