#version 330 core
// Depth pass of the shadow-mapped baseline (src/gl/shadow_map_pass.h): one part
// into one light's orthographic map. Prepended by the host: the layout
// constants and the shading core, whose shadow_map_point the shading pass
// uses too, so a vertex finds itself in the map where it was drawn.

layout(location = 0) in vec3 a_position;  // part space

uniform mat4 u_model;   // the part's pose
uniform vec3 u_light;   // the map's direction (unit, towards the light)
uniform vec4 u_sphere;  // the maps' sphere: centre, radius

void main() {
    vec3 world = (u_model * vec4(a_position, 1.0)).xyz;
    vec3 q = shadow_map_point(shadow_map_frame(u_light), u_sphere.xyz, u_sphere.w, world);
    gl_Position = vec4(2.0 * q - 1.0, 1.0);  // window depth = q.z (glDepthRange 0..1)
}
