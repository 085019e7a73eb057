// What the shading sum reads, and how (point_sum.glsl sums it): the
// host's defines, the uniforms of the scene's data (layout of every
// texture: src/gl/gpu_layout.h), the fetches by integer index, and
// the BRDF tables' square average, with the same arithmetic as the CPU
// (src/brdf/brdf_table.cpp). The host prepends, in order (gl_objects.cpp
// shading_prelude, shading_inputs_prelude): MAX_STRIDE (texels of a CPCA
// row), SVDF_STRIDE and OVDF_STRIDE (below), the layout constants of
// src/gl/gpu_layout.h (kPartStride, kSlot*, kArrayWidth, kArrayShift,
// kLightTexels, kSamplesPerTexel, kPi, kSqrt2) and the storage bindings of
// src/gl/gpu_interface.h (*_BINDING), the shading core
// src/shading/shading_core.h, whose functions (frames, the equal-area map,
// square taps, bilinear taps, the VDT rule, the OVDF's shells, faces, zoom
// and cone bounds, the slab rule) are the CPU's own, the samplers, then this
// file, visibility_fields.glsl, shadow_map_filter.glsl and, last,
// point_sum.glsl (the order of gpu_interface.h ShaderSource).
// What stays in these files is data access: texelFetch and the loops over it.

// SVDF_STRIDE, OVDF_STRIDE (the host's): the texels of a CPCA row when every
// field of the kind shares them, so that the loops over a row have a
// constant count (a software rasterizer pays a loop's every turn); 0: read
// from the field's record.
#ifndef SVDF_STRIDE
#define SVDF_STRIDE 0
#endif
#ifndef OVDF_STRIDE
#define OVDF_STRIDE 0
#endif
// LOCAL_LIGHTS (the vertex pass's define): 0 when the frame has no sphere
// lights, so that light_at compiles the environment squares' path alone.
#ifndef LOCAL_LIGHTS
#define LOCAL_LIGHTS 1
#endif

// The samplers (u_positions, u_parts, u_lights, u_brdf, ...) come before
// this file, declared from src/gl/gpu_interface.h kShadingSamplers, whose
// rows also give the host their texture units.

uniform int u_environment_lights;  // lights [0, E) are environment squares, [E, L) local sphere lights
// The exact diffuse light (src/shading/diffuse_light.h): the irradiance maps'
// nodes in u_lights after the lights, read at the normal turned into the maps' frame.
uniform int u_irradiance_resolution;  // M; 0: none (the squares' own diffuse light)
uniform int u_irradiance_first;       // the first map's node 0 in u_lights
uniform int u_irradiance_second;      // the second map's (a blend), -1 without one
uniform vec2 u_irradiance_weights;    // the blend's weights
uniform mat3 u_environment_rotation;  // the maps' frame -> the world
uniform int u_light_count;
uniform bool u_environment_enabled;  // RenderOptions::environment
uniform bool u_local_enabled;        // RenderOptions::local_lights
uniform int u_brdf_resolution;     // N
uniform int u_brdf_tiles;          // slices stacked along y per depth layer (GlRenderer::upload_all_tables)
uniform vec4 u_pbr_basis[kPbrBasisRecords];  // the basis tables' records (src/shading/pbr_basis.h), 0: not built
uniform vec3 u_camera;
uniform bool u_self_visibility;
uniform vec3 u_face_normal[kCubeFaces];  // the OVDF cube faces (as Ovdf::prepare)
uniform vec3 u_face_s[kCubeFaces];
uniform vec3 u_face_t[kCubeFaces];
// The shadow-mapped baseline (src/gl/shadow_map_pass.h): layer l = environment light l.
uniform bool u_shadow_maps;      // environment lights' visibility from the maps
uniform bool u_shadow_pcss;      // PCSS (blocker search); else PCF at u_pcf_depth
uniform vec4 u_shadow_sphere;    // the maps' sphere: centre, radius
uniform int u_shadow_resolution; // texels per side
uniform float u_shadow_texel;    // 1 / resolution: a texel, across and in depth
uniform float u_pcf_depth;       // PCF: the occluder distance assumed, in depth units


vec4 fetch(sampler2D array, int i) { return texelFetch(array, ivec2(i & (kArrayWidth - 1), i >> kArrayShift), 0); }
vec4 part_texel(int part, int slot) { return fetch(u_parts, part * kPartStride + slot); }
// A part's pose (its record): the transform, and the normals' matrix.
mat4 part_transform(int part) {
    return mat4(part_texel(part, kSlotTransform), part_texel(part, kSlotTransform + 1),
                part_texel(part, kSlotTransform + 2), part_texel(part, kSlotTransform + 3));
}
mat3 part_normal_matrix(int part) {
    return mat3(part_texel(part, kSlotNormal).xyz, part_texel(part, kSlotNormal + 1).xyz,
                part_texel(part, kSlotNormal + 2).xyz);
}
uint uint_fetch(usampler2D array, int i) { return texelFetch(array, ivec2(i & (kArrayWidth - 1), i >> kArrayShift), 0).r; }

// ---- BRDF summed-area tables (brdf_table.cpp) ----

// Average of ρ·cos over the square (table frame) for view `view`; material =
// (first slice, isotropic: 1 / view-independent too: 2 / 0, V, 0). The
// slices and their weights first, then the taps of each slice summed in
// the order of the CPU's batch kernel (brdf_table_lookup.cpp: per pair of
// columns over the rows, the column weights last), so that the two round
// alike. Software rasterizers run both sides of every branch, so the table
// reads stay out of them; MAX_SLICES (a define of the host) is the most
// slices any table of the pass needs.
#ifndef MAX_SLICES
#define MAX_SLICES 4
#endif
vec3 brdf_average(vec4 material, vec2 c, float h, vec3 view) {
    SquareTaps t = square_taps(c, h, u_brdf_resolution);
    if (t.clipped_area <= 0.0f) return vec3(0.0f);
    int first = int(material.x), v = int(material.z);
    int slice[4] = int[4](first, first, first, first);
    float weight[4] = float[4](1.0f, 0.0f, 0.0f, 0.0f);
    if (material.y > 1.5f) {  // every slice the same: the first alone, as the CPU's batch kernel
    } else if (material.y > 0.5f) {
        LerpPair k = sample_lerp(isotropic_view_coordinate(view.z, v), v);
        slice[0] = first + k.lower;
        slice[1] = first + k.lower + 1;
        weight[0] = 1.0f - k.upper_weight;
        weight[1] = k.upper_weight;
    } else {
        vec2 p = anisotropic_view_point(view);
        LerpPair i = sample_lerp(view_grid_coordinate(p.x, v), v);
        LerpPair j = sample_lerp(view_grid_coordinate(p.y, v), v);
        float wi = i.upper_weight, wj = j.upper_weight;
        int s = first + j.lower * v + i.lower;
        slice = int[4](s, s + 1, s + v, s + v + 1);
        weight = float[4]((1.0f - wi) * (1.0f - wj), wi * (1.0f - wj), (1.0f - wi) * wj, wi * wj);
    }
    // The material's own slice count bounds the loop too: a block is one
    // part, so its lanes stop together (a Lambert part reads one slice in
    // a pass whose most is four).
    int slices = material.y > 1.5f ? 1 : (material.y > 0.5f ? 2 : 4);
    // Columns ax[0], ax[1] (the first pair) and ax[2], ax[3] (the second), summed over the rows.
    vec3 first_a = vec3(0.0f), first_b = vec3(0.0f), second_a = vec3(0.0f), second_b = vec3(0.0f);
    vec3 offset = vec3(0.0f);
    ivec4 column = t.ax + t.texels * (u_brdf_resolution + 1);  // the texels sit beside the corner sums
    for (int k = 0; k < MAX_SLICES && k < slices; ++k) {
        vec3 fa = vec3(0.0f), fb = vec3(0.0f), sa = vec3(0.0f), sb = vec3(0.0f);
        // Slice s lies in depth layer s / tiles, tile s % tiles along y.
        int layer = slice[k] / u_brdf_tiles, tile_row = (slice[k] - layer * u_brdf_tiles) * (u_brdf_resolution + 1);
        for (int m = 0; m < 4; ++m) {
            float w = weight[k] * t.wy[m];
            int row = t.by[m] + tile_row;
            fa += w * texelFetch(u_brdf, ivec3(column[0], row, layer), 0).rgb;
            fb += w * texelFetch(u_brdf, ivec3(column[1], row, layer), 0).rgb;
            sa += w * texelFetch(u_brdf, ivec3(column[2], row, layer), 0).rgb;
            sb += w * texelFetch(u_brdf, ivec3(column[3], row, layer), 0).rgb;
        }
        first_a += fa;
        first_b += fb;
        second_a += sa;
        second_b += sb;
        offset += (weight[k] * t.offset_area) * fetch(u_brdf_offsets, slice[k]).rgb;
    }
    vec3 sum = (first_a * t.wx[0] + second_a * t.wx[2]) + (first_b * t.wx[1] + second_b * t.wx[3]) + offset;
    return max(sum * t.inv_full_area, vec3(0.0f));  // ≥ 0 as the CPU's: a square's differences can cancel below 0
}
