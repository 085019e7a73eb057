#version 330 core
// Display pass: the parts drawn with the vertex colours the shading pass
// wrote (attribute 1 reads the pixel-pack buffer as a vertex buffer).
layout(location = 0) in vec3 a_position;  // part space
layout(location = 1) in vec4 a_color;     // linear RGB radiance (textured parts: diffuse at unit texture)
layout(location = 2) in vec4 a_specular;  // textured parts: the specular layer (the buffer's second rectangle)
layout(location = 3) in vec2 a_texcoord;  // textured parts: glTF texture coordinates
uniform mat4 u_model;
uniform mat4 u_view_projection;
out vec3 v_color;
out vec3 v_specular;
out vec2 v_texcoord;
void main() {
    v_color = a_color.rgb;
    v_specular = a_specular.rgb;
    v_texcoord = a_texcoord;
    gl_Position = u_view_projection * (u_model * vec4(a_position, 1.0));
}
