// Any-hit shadow rays through the two-level BVH of src/gl/gpu_bvh.h
// (docs/design/GPU_DESIGN.md "Ray-traced visibility"). The host defines the
// BVH_* sizes (GpuBvh::shader_defines) and prepends the shading core, with
// the bindings (src/gl/gpu_interface.h).

layout(std430, binding = BVH_NODES_BINDING) readonly buffer BvhNodes { vec4 bvh_nodes[]; };
layout(std430, binding = BVH_TRIANGLES_BINDING) readonly buffer BvhTriangles { vec4 bvh_triangles[]; };
layout(std430, binding = BVH_INSTANCES_BINDING) readonly buffer BvhInstances { vec4 bvh_instances[]; };

uniform int u_bvh_top_root;  // the top level's root node
uniform int u_bvh_parts;     // where the top level's part order starts (after the records)

// The part's posed box diagonal (RayScene::instance_diagonal): the scale of its ray offsets.
float bvh_instance_diagonal(int part) { return bvh_instances[part * BVH_INSTANCE_VEC4S + 10].x; }

// Whether the ray enters the box before t_far (slab test; the far side
// widened by a few ulps so that a ray along a face still enters).
bool bvh_box_hit(vec3 lo, vec3 hi, vec3 origin, vec3 inverse_direction, float t_far) {
    vec3 a = (lo - origin) * inverse_direction, b = (hi - origin) * inverse_direction;
    vec3 near = min(a, b), far = max(a, b);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), min(far.z, t_far)) * 1.0000004;
    return enter <= leave;
}

// Child c of node `node` as the ray sees it: (first index, count) of the
// child the ray enters (count 0: an inner node, to push; else a leaf's first
// entry and entries), count -1 when it misses or the child is empty (10³⁰),
// so that a loop over a leaf's entries runs for leaves alone.
ivec2 bvh_child(int node, int c, vec3 origin, vec3 inverse_direction, float t_far) {
    vec4 lo = bvh_nodes[node * BVH_NODE_VEC4S + 2 * c], hi = bvh_nodes[node * BVH_NODE_VEC4S + 2 * c + 1];
    if (lo.x >= 1e30 || !bvh_box_hit(lo.xyz, hi.xyz, origin, inverse_direction, t_far)) return ivec2(0, -1);
    return ivec2(floatBitsToInt(lo.w), floatBitsToInt(hi.w));
}

// Blocked by part `part`'s triangles (ray in the part's frame)? A hit within
// `exit_t` that the ray leaves through the triangle's front is ignored
// (RayScene's origins_outside_surfaces filter).
bool bvh_part_occluded(int part, vec3 origin, vec3 direction, float t_far, float exit_t) {
    vec3 inverse_direction = 1.0 / direction;
    int stack[BVH_STACK];
    int top = 0;
    int node = floatBitsToInt(bvh_instances[part * BVH_INSTANCE_VEC4S + 8].w);
    while (true) {
        for (int c = 0; c < 2; ++c) {
            ivec2 child = bvh_child(node, c, origin, inverse_direction, t_far);
            if (child.y == 0) stack[top++] = child.x;
            for (int t = child.x; t < child.x + child.y; ++t) {  // a leaf's triangles (none: a miss or an inner node); Möller–Trumbore
                vec3 v0 = bvh_triangles[t * BVH_TRIANGLE_VEC4S].xyz;
                vec3 e1 = bvh_triangles[t * BVH_TRIANGLE_VEC4S + 1].xyz;
                vec3 e2 = bvh_triangles[t * BVH_TRIANGLE_VEC4S + 2].xyz;
                vec3 p = cross(direction, e2);
                float det = dot(e1, p);
                if (det == 0.0) continue;
                float inverse_det = 1.0 / det;
                vec3 s = origin - v0;
                float u = dot(s, p) * inverse_det;
                if (u < 0.0 || u > 1.0) continue;
                vec3 q = cross(s, e1);
                float v = dot(direction, q) * inverse_det;
                if (v < 0.0 || u + v > 1.0) continue;
                float t_hit = dot(e2, q) * inverse_det;
                if (!(t_hit > 0.0 && t_hit < t_far)) continue;
                if (t_hit < exit_t && dot(direction, cross(e1, e2)) > 0.0) continue;  // leaving its own surface
                return true;
            }
        }
        if (top == 0) return false;
        node = stack[--top];
    }
    return false;
}

// Whether the ray from `origin` along `direction` (any length; t_far in its
// units) is blocked by any part: the top level, then each part's own level.
bool bvh_occluded(vec3 origin, vec3 direction, float t_far) {
    float inverse_length = 1.0 / length(direction);
    float position_exit = kRayExitOffsets * ray_offset_distance(0.0, origin);
    vec3 inverse_direction = 1.0 / direction;
    int stack[BVH_STACK];
    int top = 0;
    int node = u_bvh_top_root;
    while (true) {
        for (int c = 0; c < 2; ++c) {
            ivec2 child = bvh_child(node, c, origin, inverse_direction, t_far);
            if (child.y == 0) stack[top++] = child.x;
            for (int i = child.x; i < child.x + child.y; ++i) {  // a leaf's parts
                int part = int(bvh_instances[u_bvh_parts * BVH_INSTANCE_VEC4S + i / 4][i % 4]);
                int record = part * BVH_INSTANCE_VEC4S;
                mat4 inverse = mat4(bvh_instances[record], bvh_instances[record + 1], bvh_instances[record + 2],
                                    bvh_instances[record + 3]);
                float exit_t = (bvh_instances[record + 10].y + position_exit) * inverse_length;
                if (bvh_part_occluded(part, (inverse * vec4(origin, 1.0)).xyz, mat3(inverse) * direction, t_far, exit_t))
                    return true;
            }
        }
        if (top == 0) return false;
        node = stack[--top];
    }
    return false;
}
