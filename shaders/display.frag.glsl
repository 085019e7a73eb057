#version 330 core
// Exposure and the sRGB transfer curve (srgb.glsl, as src/formats/image_file.h's tone-mapped PNG).
// A textured part is formed as the CPU's image formation does it: the
// interpolated diffuse layer times the base colour texture per pixel (linear
// RGB, bilinear between texel centers, the sampler's wrap modes), plus the
// interpolated specular layer. An emitting part adds its emission at the
// pixel's texture coordinates (the colour buffer holds none; the CPU's
// image formation takes the vertices' out of its blend and adds the pixel's).
in vec3 v_color;
in vec3 v_specular;
in vec2 v_texcoord;
uniform float u_exposure;
uniform bool u_linear;  // linear radiance (images read back); else exposure and sRGB (the screen)
uniform bool u_textured;
uniform sampler2D u_base_color;
uniform vec3 u_emissive;  // the part's emission factor (src/core/emission.h)
uniform bool u_emissive_textured;
uniform sampler2D u_emissive_texture;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 color = u_textured ? v_color * texture(u_base_color, v_texcoord).rgb + v_specular : v_color;
    color += u_emissive_textured ? u_emissive * texture(u_emissive_texture, v_texcoord).rgb : u_emissive;
    o_color = u_linear ? vec4(color, 1.0) : vec4(srgb(color * u_exposure), 1.0);
}
