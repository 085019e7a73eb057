#version 330 core
// The environment seen through each pixel: the view ray's direction d in the
// world, the map's radiance L(Rᵀ d) (its content at d has turned by R, as the
// renderer's lights have; docs/design/CONVENTIONS.md), the nearest texel of each map
// blended as the renderer blends their lights; exposure and the sRGB curve
// (srgb.glsl) as the display pass.
in vec2 v_ndc;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform mat3 u_rotation_transpose;
uniform samplerCube u_first, u_second;
uniform float u_second_weight;
uniform float u_exposure;
layout(location = 0) out vec4 o_color;
void main() {
    vec4 far = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
    vec3 direction = u_rotation_transpose * normalize(far.xyz / far.w - u_eye);
    vec3 radiance = texture(u_first, direction).rgb;
    if (u_second_weight > 0.0) radiance = mix(radiance, texture(u_second, direction).rgb, u_second_weight);
    o_color = vec4(srgb(radiance * u_exposure), 1.0);
}
