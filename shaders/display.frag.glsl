#version 330 core
// Exposure and the sRGB transfer curve (as src/core/image.h's tone-mapped PNG).
in vec3 v_color;
uniform float u_exposure;
layout(location = 0) out vec4 o_color;
vec3 srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() { o_color = vec4(srgb(v_color * u_exposure), 1.0); }
