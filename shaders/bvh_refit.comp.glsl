#version 430 core
// The top level's boxes from the frame's poses (src/gl/gpu_bvh.h): one
// workgroup visits the top nodes level by level, deepest first, so that a
// node's children are final before it reads them. A leaf child's box is its
// parts' mesh boxes posed (eight corners, as the host's RayScene boxes).
// The host prepends the bindings (src/gl/gpu_interface.h) and the BVH_* sizes.
layout(local_size_x = 256) in;

layout(std430, binding = BVH_NODES_BINDING) buffer BvhNodes { vec4 bvh_nodes[]; };
layout(std430, binding = BVH_INSTANCES_BINDING) readonly buffer BvhInstances { vec4 bvh_instances[]; };
layout(std430, binding = BVH_LEVELS_BINDING) readonly buffer Levels { int levels[]; };  // top nodes, deepest level first

uniform int u_level_count;
uniform int u_level_ends[BVH_STACK];  // per level, its end in levels[] (GpuBvh: at most kBvhStack levels)
uniform int u_parts;

void grow(inout vec3 lo, inout vec3 hi, vec3 p) {
    lo = min(lo, p);
    hi = max(hi, p);
}

void main() {
    int begin = 0;
    for (int level = 0; level < u_level_count; ++level) {
        int end = u_level_ends[level];
        for (int i = begin + int(gl_LocalInvocationID.x); i < end; i += 256) {
            int node = levels[i];
            for (int c = 0; c < 2; ++c) {
                vec4 lo = bvh_nodes[node * BVH_NODE_VEC4S + 2 * c], hi = bvh_nodes[node * BVH_NODE_VEC4S + 2 * c + 1];
                int index = floatBitsToInt(lo.w), count = floatBitsToInt(hi.w);
                if (lo.x >= 1e30) continue;  // an empty child (GpuBvh: a point box at 10³⁰)
                vec3 box_lo = vec3(1e30), box_hi = vec3(-1e30);
                if (count == 0) {  // a node: its two children's boxes
                    for (int k = 0; k < 2; ++k) {
                        grow(box_lo, box_hi, bvh_nodes[index * BVH_NODE_VEC4S + 2 * k].xyz);
                        grow(box_lo, box_hi, bvh_nodes[index * BVH_NODE_VEC4S + 2 * k + 1].xyz);
                    }
                } else {
                    for (int j = index; j < index + count; ++j) {
                        int part = int(bvh_instances[u_parts * BVH_INSTANCE_VEC4S + j / 4][j % 4]);
                        int record = part * BVH_INSTANCE_VEC4S;
                        mat4 transform = mat4(bvh_instances[record + 4], bvh_instances[record + 5],
                                              bvh_instances[record + 6], bvh_instances[record + 7]);
                        vec3 mesh_lo = bvh_instances[record + 8].xyz, mesh_hi = bvh_instances[record + 9].xyz;
                        for (int corner = 0; corner < 8; ++corner) {
                            vec3 p = vec3((corner & 1) != 0 ? mesh_hi.x : mesh_lo.x, (corner & 2) != 0 ? mesh_hi.y : mesh_lo.y,
                                          (corner & 4) != 0 ? mesh_hi.z : mesh_lo.z);
                            grow(box_lo, box_hi, (transform * vec4(p, 1.0)).xyz);
                        }
                    }
                    // The world box holds the posed triangles beyond float rounding.
                    vec3 pad = 1e-6 * (abs(box_lo) + abs(box_hi) + (box_hi - box_lo));
                    box_lo -= pad;
                    box_hi += pad;
                }
                bvh_nodes[node * BVH_NODE_VEC4S + 2 * c] = vec4(box_lo, lo.w);
                bvh_nodes[node * BVH_NODE_VEC4S + 2 * c + 1] = vec4(box_hi, hi.w);
            }
        }
        memoryBarrierBuffer();
        barrier();
        begin = end;
    }
}
