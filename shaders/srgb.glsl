// The sRGB transfer curve of the viewer's passes (display.frag.glsl,
// skybox.frag.glsl), as src/formats/image_file.h's tone-mapped PNG; the host puts it
// before a shader's own text (gl_objects.h srgb_prelude).
vec3 srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
