#version 430 core
// Occlusion of a batch of rays through the BVH (GpuBvh::occluded): per ray
// (origin, direction) in rays[2i], rays[2i + 1], 1 when blocked before u_t_far.
// The host prepends the BVH_* sizes, the shading core (with the bindings of
// src/gl/gpu_interface.h) and bvh_traverse.glsl.
layout(local_size_x = 64) in;

layout(std430, binding = RAYS_BINDING) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = HITS_BINDING) writeonly buffer Hits { uint hits[]; };

uniform int u_ray_count;
uniform float u_t_far;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_ray_count) return;
    hits[i] = bvh_occluded(rays[2 * i].xyz, rays[2 * i + 1].xyz, u_t_far) ? 1u : 0u;
}
