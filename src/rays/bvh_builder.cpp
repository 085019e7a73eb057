#include "src/rays/bvh_builder.h"

#include <algorithm>
#include <array>

namespace rsl {

namespace {

float half_area(const Bounds& b) {
    if (b.empty()) return 0.0f;
    const Vec3 d = b.hi - b.lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

Bounds merged(const Bounds& a, const Bounds& b) {
    Bounds m = a;
    if (!b.empty()) m.extend(b.lo), m.extend(b.hi);
    return m;
}

struct Builder {
    const std::vector<Bounds>& boxes;
    const BvhBuildOptions& options;
    std::vector<Vec3> centroids;
    BvhTree tree;

    Bounds box_of(int first, int count) const {
        Bounds b;
        for (int i = first; i < first + count; ++i) b = merged(b, boxes[size_t(tree.order[size_t(i)])]);
        return b;
    }

    // Where to split order[first, first + count): the SAH's best bin
    // boundary along the widest centroid axis, or the middle (by centroid)
    // where the centroids do not spread; returns the left count (0: no split).
    int split(int first, int count) {
        Bounds spread;
        for (int i = first; i < first + count; ++i) spread.extend(centroids[size_t(tree.order[size_t(i)])]);
        const Vec3 extent = spread.hi - spread.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        int* begin = tree.order.data() + first;
        int* end = begin + count;
        if (!(extent[axis] > 0.0f)) return count / 2;  // coincident centroids: any halves
        const int bins = options.bins;
        std::vector<Bounds> bin_box(static_cast<size_t>(bins));
        std::vector<int> bin_count(static_cast<size_t>(bins), 0);
        const float scale = float(bins) / extent[axis];
        auto bin_of = [&](int primitive) {
            return std::min(bins - 1, int((centroids[size_t(primitive)][axis] - spread.lo[axis]) * scale));
        };
        for (const int* p = begin; p != end; ++p) {
            const int b = bin_of(*p);
            bin_box[size_t(b)] = merged(bin_box[size_t(b)], boxes[size_t(*p)]);
            ++bin_count[size_t(b)];
        }
        // Cost of each boundary from the left and right sweeps.
        std::vector<float> left_cost(static_cast<size_t>(bins), 0.0f);
        Bounds left;
        int left_count = 0;
        for (int b = 0; b < bins - 1; ++b) {
            left = merged(left, bin_box[size_t(b)]);
            left_count += bin_count[size_t(b)];
            left_cost[size_t(b)] = half_area(left) * float(left_count);
        }
        Bounds right;
        int right_count = 0, best = -1;
        float best_cost = 0.0f;
        for (int b = bins - 1; b > 0; --b) {
            right = merged(right, bin_box[size_t(b)]);
            right_count += bin_count[size_t(b)];
            const float cost = left_cost[size_t(b - 1)] + half_area(right) * float(right_count);
            if (right_count < count && (best < 0 || cost < best_cost)) best = b - 1, best_cost = cost;
        }
        if (best < 0) return count / 2;
        int* middle = std::partition(begin, end, [&](int primitive) { return bin_of(primitive) <= best; });
        const int n = int(middle - begin);
        return n == 0 || n == count ? count / 2 : n;
    }

    // The child for order[first, first + count) at `depth` (the root's children: 1).
    BvhChild child(int first, int count, int depth) {
        tree.depth = std::max(tree.depth, depth + 1);
        BvhChild c;
        c.box = box_of(first, count);
        if (count <= options.max_leaf || depth >= options.max_depth) {
            c.index = first, c.count = count;
            return c;
        }
        c.index = node(first, count, depth);
        return c;
    }

    int node(int first, int count, int depth) {
        const int index = int(tree.nodes.size());
        tree.nodes.emplace_back();
        int left = split(first, count);
        if (left == 0) left = count / 2;
        const BvhChild a = child(first, left, depth + 1);
        const BvhChild b = child(first + left, count - left, depth + 1);
        tree.nodes[size_t(index)].child[0] = a;
        tree.nodes[size_t(index)].child[1] = b;
        return index;
    }
};

}  // namespace

BvhTree build_bvh(const std::vector<Bounds>& boxes, const BvhBuildOptions& options) {
    Builder builder{boxes, options, {}, {}};
    const int count = int(boxes.size());
    builder.tree.order.resize(boxes.size());
    for (int i = 0; i < count; ++i) builder.tree.order[size_t(i)] = i;
    for (const Bounds& b : boxes) builder.centroids.push_back(b.center());
    builder.tree.depth = 1;
    if (count <= 1) {  // a root with one leaf (or none) and an empty child
        BvhNode root;
        root.child[0].count = count;
        if (count == 1) root.child[0].box = boxes[0];
        builder.tree.nodes.push_back(root);
        return std::move(builder.tree);
    }
    builder.node(0, count, 0);
    return std::move(builder.tree);
}

std::vector<Bounds> triangle_boxes(const TriangleMesh& mesh) {
    std::vector<Bounds> boxes(mesh.triangle_count());
    for (size_t t = 0; t < boxes.size(); ++t)
        for (int k = 0; k < 3; ++k) boxes[t].extend(mesh.positions[mesh.indices[3 * t + size_t(k)]]);
    return boxes;
}

}  // namespace rsl
