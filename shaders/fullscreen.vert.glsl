#version 330 core
// A triangle covering the viewport, with no vertex buffer: the shading pass
// runs its fragment shader once per texel of the vertex rectangle.
void main() {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
