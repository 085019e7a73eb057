#version 330 core
// Display pass: the parts drawn with the vertex colours the shading pass
// wrote (attribute 1 reads the pixel-pack buffer as a vertex buffer).
layout(location = 0) in vec3 a_position;  // part space
layout(location = 1) in vec4 a_color;     // linear RGB radiance
uniform mat4 u_model;
uniform mat4 u_view_projection;
out vec3 v_color;
void main() {
    v_color = a_color.rgb;
    gl_Position = u_view_projection * (u_model * vec4(a_position, 1.0));
}
