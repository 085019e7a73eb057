#version 330 core
// The per-pixel pass (RenderOptions::pixel_shadows; docs/GPU.md "Per-pixel
// shadows"): each pixel of a part shaded per pixel — one flat rectangle (a
// ground, a floor, a wall), whose vertices are often coarser than the
// shadows that fall on it — takes the whole sum at the point it sees
// (shade_point.glsl): the other parts' occluder factor, the BRDF averages at
// its own view, local lights from its own position. A flat rectangle cannot
// shadow itself, so its self-visibility is 1 and no SVDF is read. The CPU
// forms the same pixels from the vertices' terms (src/render/pixel_shading.cpp).
in vec3 v_position;
in vec3 v_normal;
in vec3 v_tangent;
in vec2 v_texcoord;
uniform int u_part;
uniform float u_exposure;
uniform bool u_linear;    // linear radiance (images read back); else exposure and sRGB (the screen)
uniform bool u_textured;  // the diffuse sum times the base colour texture, plus the specular sum
uniform sampler2D u_base_color;
layout(location = 0) out vec4 o_color;
void main() {
    // The side the camera sees, as the CPU's hit point (PosedScene::hit_point).
    vec3 n = normalize(v_normal);
    if (dot(n, u_camera - v_position) < 0.0) n = -n;
    PointShade shaded = shade_point(u_part, v_position, frame_rows(n, v_tangent), false, 0);
    vec3 color = u_textured ? shaded.color * texture(u_base_color, v_texcoord).rgb + shaded.specular : shaded.color;
    o_color = u_linear ? vec4(color, 1.0) : vec4(srgb(color * u_exposure), 1.0);
}
