// The ray-traced baseline's visibility in the vertex pass
// (RenderOptions::gpu_rays; docs/design/GPU_DESIGN.md "Ray-traced
// visibility"): S×S jittered shadow rays per vertex and light, traced
// through the posed parts' BVH (bvh_traverse.glsl, included before this
// file). The rays are the CPU's ray-traced rows' (src/render/exact_visibility.cpp):
// the same seeds, grid points and ray origins (src/shading/ray_samples.h).

// Per vertex (vertex rectangle order): the part-space direction into its
// own triangles where it lies on its surface's border, else 0 (binding: kBindingRayInward, src/gl/gpu_interface.h).
layout(std430, binding = RAY_INWARD_BINDING) readonly buffer RayInward { vec4 ray_inward[]; };

uniform int u_ray_samples;  // S

// Where the vertex's rays start (PosedScene::vertex, SurfacePoint::ray_origin):
// a border vertex first moves one ray offset into its own triangles, then
// every vertex one offset along its shading normal.
vec3 ray_origin(int part, int vertex, vec3 p, mat3 linear, vec3 normal) {
    float scale = bvh_instance_diagonal(part);
    vec3 inward = ray_inward[vertex].xyz;
    if (inward != vec3(0.0)) p += normalize(linear * inward) * ray_offset_distance(scale, p);
    return p + normal * ray_offset_distance(scale, p);
}

// The visible share of light `light`'s square (plane centre c, half-edge h
// in the vertex's frame) at vertex `local_vertex` of `part`: the S×S grid's
// points above the horizon that reach the sky over those above it (1 when
// none is); a direction into the surface counts as blocked. `rays` counts
// the rays traced.
float ray_traced_fraction(int part, int local_vertex, int light, vec3 origin, LocalFrame frame, vec2 c, float h,
                          inout uint rays) {
    uvec2 seed = ray_seed(part, local_vertex, light);
    int counted = 0, reached = 0;
    for (int j = 0; j < u_ray_samples; ++j)
        for (int i = 0; i < u_ray_samples; ++i) {
            vec2 q = square_grid_point(c, h, u_ray_samples, i, j, jitter_in_cell(seed, j * u_ray_samples + i));
            if (dot(q, q) >= 1.0) continue;  // below the shading horizon
            vec3 direction = frame_to_world(frame, plane_to_hemisphere(q));
            ++counted;
            if (!(dot(direction, frame.z) > 0.0)) continue;
            ++rays;
            if (!bvh_occluded(origin, direction, 1e30)) ++reached;
        }
    return counted > 0 ? float(reached) / float(counted) : 1.0;
}
