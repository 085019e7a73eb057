#version 330 core
// Exposure and the sRGB transfer curve (srgb.glsl, as src/core/image.h's tone-mapped PNG).
in vec3 v_color;
uniform float u_exposure;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(srgb(v_color * u_exposure), 1.0); }
