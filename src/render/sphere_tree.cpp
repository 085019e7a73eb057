#include "src/render/sphere_tree.h"

#include <algorithm>

namespace rsl {

namespace {

constexpr int kLeafSize = 4;

// Squared distance from p to the box (0 inside).
float distance2_to_box(const Vec3& p, const Bounds& box) {
    const Vec3 d = glm::max(glm::max(box.lo - p, p - box.hi), Vec3(0.0f));
    return glm::dot(d, d);
}

}  // namespace

void SphereTree::build(std::span<const BoundingSphere> spheres) {
    spheres_.assign(spheres.begin(), spheres.end());
    ids_.resize(spheres_.size());
    for (size_t i = 0; i < ids_.size(); ++i) ids_[i] = int(i);
    nodes_.clear();
    if (!spheres_.empty()) build_node(0, int(ids_.size()));
}

// Median split of the centres along their longest axis.
int SphereTree::build_node(int begin, int count) {
    const int index = int(nodes_.size());
    nodes_.push_back(Node{Bounds{}, begin, count});
    Bounds box, centers;
    for (int i = begin; i < begin + count; ++i) {
        const BoundingSphere& s = spheres_[size_t(ids_[size_t(i)])];
        box.extend(s.center - Vec3(s.radius));
        box.extend(s.center + Vec3(s.radius));
        centers.extend(s.center);
    }
    nodes_[size_t(index)].box = box;
    if (count <= kLeafSize) return index;
    const Vec3 extent = centers.hi - centers.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const int half = count / 2;
    const auto first = ids_.begin() + begin;
    std::nth_element(first, first + half, first + count,
                     [&](int a, int b) { return spheres_[size_t(a)].center[axis] < spheres_[size_t(b)].center[axis]; });
    const int left = build_node(begin, half);
    const int right = build_node(begin + half, count - half);
    nodes_[size_t(index)].left = left;
    nodes_[size_t(index)].right = right;
    return index;
}

void SphereTree::overlapping(const BoundingSphere& query, std::vector<int>& out) const {
    if (nodes_.empty()) return;
    const size_t first = out.size();
    const float margin = 1.0f + 1e-5f;
    const float reach = query.radius * margin;
    // Median splits keep the depth below 32, and a depth-first walk holds at
    // most one pending sibling per level.
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[size_t(stack[--top])];
        if (distance2_to_box(query.center, node.box) > reach * reach) continue;
        if (node.left >= 0) {
            stack[top++] = node.left;
            stack[top++] = node.right;
            continue;
        }
        for (int i = node.begin; i < node.begin + node.count; ++i) {
            const BoundingSphere& s = spheres_[size_t(ids_[size_t(i)])];
            if (glm::length(query.center - s.center) <= (query.radius + s.radius) * margin) out.push_back(ids_[size_t(i)]);
        }
    }
    std::sort(out.begin() + std::ptrdiff_t(first), out.end());
}

}  // namespace rsl
