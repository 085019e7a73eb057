// `rsl bench bvh`: the GPU rays' bottom-level builder (src/rays/bvh_builder.h)
// against Embree's own builder (rtcBuildBVH, binary, the same leaf size) on
// the shipped meshes: build time and the trees' SAH cost (the expected
// work of a ray, in box tests and triangle tests), which is what traversal pays.
#include <embree3/rtcore.h>

#include <new>

#include "src/core/error.h"
#include "src/fields/field_cache.h"
#include "src/formats/scene_file.h"
#include "src/rays/bvh_builder.h"
#include "tools/bench/bench.h"

namespace rsl::bench {
namespace {

float half_area(const Bounds& b) {
    const Vec3 d = b.hi - b.lo;
    return b.empty() ? 0.0f : d.x * d.y + d.y * d.z + d.z * d.x;
}

// SAH cost of a tree, relative to its root box: Σ over inner nodes of
// area × 2 box tests + Σ over leaves of area × triangles.
struct SahCost {
    double boxes = 0, triangles = 0;
    double total() const { return boxes + triangles; }
};

SahCost sah_cost(const BvhTree& tree) {
    Bounds root;
    for (const BvhChild& c : tree.nodes[0].child)
        if (!c.box.empty()) root.extend(c.box.lo), root.extend(c.box.hi);
    SahCost cost;
    const double scale = 1.0 / half_area(root);
    cost.boxes += 2.0;  // the root's two boxes
    for (const BvhNode& node : tree.nodes)
        for (const BvhChild& c : node.child) {
            if (c.box.empty()) continue;
            if (c.count > 0) cost.triangles += scale * half_area(c.box) * c.count;
            else cost.boxes += scale * half_area(c.box) * 2.0;
        }
    return cost;
}

// Embree's tree, in its allocator's memory.
struct EmbreeNode {
    Bounds box[2];
    EmbreeNode* child[2] = {nullptr, nullptr};
    int count[2] = {0, 0};  // leaves: primitives
    bool leaf = false;
    int primitives = 0;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int, void*) {
    return new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeNode), 16)) EmbreeNode();
}
void set_children(void* node, void** children, unsigned int count, void*) {
    for (unsigned int i = 0; i < count && i < 2; ++i) static_cast<EmbreeNode*>(node)->child[i] = static_cast<EmbreeNode*>(children[i]);
}
void set_bounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
    for (unsigned int i = 0; i < count && i < 2; ++i) {
        Bounds& b = static_cast<EmbreeNode*>(node)->box[i];
        b.lo = Vec3(bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z);
        b.hi = Vec3(bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z);
    }
}
void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive*, size_t count, void*) {
    auto* leaf = new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeNode), 16)) EmbreeNode();
    leaf->leaf = true;
    leaf->primitives = int(count);
    return leaf;
}

// Embree's tree as a BvhTree (boxes and leaf sizes only), for the same SAH measure.
void flatten(const EmbreeNode* node, BvhTree& tree) {
    const int index = int(tree.nodes.size());
    tree.nodes.emplace_back();
    for (int i = 0; i < 2; ++i) {
        const EmbreeNode* c = node->child[i];
        if (!c) continue;
        BvhChild child;
        child.box = node->box[i];
        if (c->leaf) {
            child.count = c->primitives;
        } else {
            child.index = int(tree.nodes.size());
            flatten(c, tree);
        }
        tree.nodes[size_t(index)].child[i] = child;
    }
}

struct EmbreeBuild {
    double seconds = 0;
    BvhTree tree;
};

EmbreeBuild embree_build(const std::vector<Bounds>& boxes, const BvhBuildOptions& options, int repeats) {
    RTCDevice device = rtcNewDevice("threads=1");
    if (!device) throw_error("Embree: no device");
    EmbreeBuild result;
    result.seconds = 1e30;
    std::vector<RTCBuildPrimitive> primitives(boxes.size() * 2);  // spare capacity for the builder
    for (int r = 0; r < repeats; ++r) {
        for (size_t i = 0; i < boxes.size(); ++i) {
            RTCBuildPrimitive& p = primitives[i];
            p.lower_x = boxes[i].lo.x, p.lower_y = boxes[i].lo.y, p.lower_z = boxes[i].lo.z, p.geomID = 0;
            p.upper_x = boxes[i].hi.x, p.upper_y = boxes[i].hi.y, p.upper_z = boxes[i].hi.z, p.primID = unsigned(i);
        }
        RTCBVH bvh = rtcNewBVH(device);
        RTCBuildArguments args = rtcDefaultBuildArguments();
        args.byteSize = sizeof(args);
        args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
        args.maxBranchingFactor = 2;
        args.maxDepth = unsigned(options.max_depth + 1);
        args.minLeafSize = 1;
        args.maxLeafSize = unsigned(options.max_leaf);
        args.bvh = bvh;
        args.primitives = primitives.data();
        args.primitiveCount = boxes.size();
        args.primitiveArrayCapacity = primitives.size();
        args.createNode = create_node;
        args.setNodeChildren = set_children;
        args.setNodeBounds = set_bounds;
        args.createLeaf = create_leaf;
        const auto start = BenchClock::now();
        const auto* root = static_cast<const EmbreeNode*>(rtcBuildBVH(&args));
        result.seconds = std::min(result.seconds, seconds_since(start));
        if (r + 1 == repeats) {
            result.tree = BvhTree{};
            if (root) flatten(root, result.tree);
        }
        rtcReleaseBVH(bvh);
    }
    rtcReleaseDevice(device);
    return result;
}

void bench_builders(const BenchOptions& options) {
    for (const char* name : {"robot.json", "../external/bunny.json", "kitchen.json"}) {
        const std::filesystem::path path = options.scenes / name;
        if (!std::filesystem::exists(path)) continue;
        const Scene scene = load_scene(path);
        for (const MeshInstances& group : group_instances(scene)) {
            const TriangleMesh& mesh = scene.parts[size_t(group.parts.front())].mesh;
            if (mesh.triangle_count() < (options.quick ? 1000u : 200u)) continue;
            const std::vector<Bounds> boxes = triangle_boxes(mesh);
            BvhBuildOptions build;
            build.max_depth = 30;  // GpuBvh's
            BvhTree ours;
            const double ours_seconds = best_seconds(3, [&] { ours = build_bvh(boxes, build); });
            const EmbreeBuild embree = embree_build(boxes, build, 3);
            const SahCost ours_cost = sah_cost(ours), embree_cost = sah_cost(embree.tree);
            bench_emit({{"bench", "bvh"},
                        {"case", scene.name + " " + mesh.name},
                        {"triangles", mesh.triangle_count()},
                        {"ours_ms", 1e3 * ours_seconds},
                        {"embree_ms", 1e3 * embree.seconds},
                        {"ours_nodes", ours.nodes.size()},
                        {"embree_nodes", embree.tree.nodes.size()},
                        {"ours_depth", ours.depth},
                        {"ours_sah", ours_cost.total()},
                        {"embree_sah", embree_cost.total()},
                        {"ours_sah_triangles", ours_cost.triangles},
                        {"embree_sah_triangles", embree_cost.triangles}});
        }
    }
}

RegisterBenchmark bvh_benchmark({"bvh",
    "GPU rays' bottom-level BVH: our binned SAH against Embree's rtcBuildBVH (one thread): build ms and SAH cost",
    [](const BenchOptions& options) { bench_builders(options); }});

}  // namespace
}  // namespace rsl::bench
