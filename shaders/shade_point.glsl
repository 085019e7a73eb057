// The shading sum at one point (RSL paper §5.2, Figure 8):
//
//   Σ_lights  2r²·I  ×  BRDF-SAT average  ×  SVDF average  ×  Π_occluders OVDF average
//
// with the same arithmetic as the CPU renderer (src/render/shade_block.cpp,
// src/brdf/brdf_table.cpp, src/fields/svdf.h, src/fields/ovdf.cpp), so that the two
// agree to float rounding. Layout of every texture: src/gl/gpu_layout.h.
// Two passes run it: the vertex pass (shade_blocks.comp.glsl, one
// invocation per vertex, which takes its functions apart to share the
// light-independent half of each lookup) and the per-pixel pass (shade_pixels.*.glsl, the
// parts shaded per pixel drawn from the camera). The host prepends, in
// order (gl_objects.cpp shading_prelude, shade_point_prelude): MAX_STRIDE
// (texels of a CPCA row), SVDF_STRIDE and OVDF_STRIDE (below), the layout constants of src/gl/gpu_layout.h
// (kPartStride, kSlot*, kArrayWidth, kArrayShift, kLightTexels,
// kSamplesPerTexel, kPi, kSqrt2), the shading core
// src/shading/shading_core.h, whose functions (frames, the equal-area map,
// square taps, bilinear taps, the VDT rule, the OVDF's shells, faces, zoom
// and cone bounds, the slab rule) are the CPU's own, then this file. What
// stays here is data access: texelFetch and the loops over it.
//
// With u_shadow_maps (RenderOptions::shadow_maps, a competitor baseline;
// docs/design/GPU_DESIGN.md "Shadow-mapped visibility") every environment light's
// visibility comes from its depth map instead (shadow_visible_fraction).

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

uniform sampler2D u_positions;     // vertex rectangle: part-space position, part
uniform sampler2D u_normals;       // normal, SVDF cluster
uniform sampler2D u_tangents;      // tangent
uniform sampler2D u_parts;         // part records (kPartStride texels each)
uniform sampler2D u_lights;        // kLightTexels per light
uniform usampler2D u_occluder_lists;  // FrameState::occluder_list_texels: offsets, then part indices
uniform sampler3D u_brdf;          // per slice: rows of corner sums, then texels (append_texture_rows)
uniform sampler2D u_brdf_offsets;  // per slice mean offset
uniform sampler2D u_svdf_tables;
uniform sampler2D u_svdf_coefficients;
uniform sampler2D u_ovdf_tables;
uniform sampler2D u_ovdf_coefficients;
uniform sampler2D u_ovdf_frames;

uniform int u_environment_lights;  // lights [0, E) are environment squares, [E, L) local sphere lights
uniform int u_light_count;
uniform bool u_environment_enabled;  // RenderOptions::environment
uniform bool u_local_enabled;        // RenderOptions::local_lights
uniform int u_brdf_resolution;     // N
uniform vec3 u_camera;
uniform bool u_self_visibility;
uniform vec3 u_face_normal[kCubeFaces];  // the OVDF cube faces (as Ovdf::prepare)
uniform vec3 u_face_s[kCubeFaces];
uniform vec3 u_face_t[kCubeFaces];
// The shadow-mapped baseline (src/gl/shadow_maps.h): layer l = environment light l.
uniform bool u_shadow_maps;      // environment lights' visibility from the maps
uniform bool u_shadow_pcss;      // PCSS (blocker search); else PCF at u_pcf_depth
uniform sampler2DArray u_shadow_depths;  // the maps (read with texelFetch)
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
uint list_texel(int i) { return uint_fetch(u_occluder_lists, i); }

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
        for (int m = 0; m < 4; ++m) {
            float w = weight[k] * t.wy[m];
            fa += w * texelFetch(u_brdf, ivec3(column[0], t.by[m], slice[k]), 0).rgb;
            fb += w * texelFetch(u_brdf, ivec3(column[1], t.by[m], slice[k]), 0).rgb;
            sa += w * texelFetch(u_brdf, ivec3(column[2], t.by[m], slice[k]), 0).rgb;
            sb += w * texelFetch(u_brdf, ivec3(column[3], t.by[m], slice[k]), 0).rgb;
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

// ---- visibility distance tables (src/fields/vdt.h, svdf.h, ovdf.cpp) ----

// The self-visibility shade_point multiplies each light by: g_self_corners
// = 0: none (a flat rectangle, or the SVDF switched off); 1: the vertex's
// own SVDF (the vertex pass); 3: the blend of a triangle's corners' SVDFs,
// each in its corner's own frame (the per-pixel pass on glossy parts, as
// the CPU blends the corners' kept terms). Corner c: its CPCA
// coefficients at g_svdf_coefficients[c·MAX_STRIDE …], its cluster (< 0:
// no SVDF), barycentric weight and shading frame.
// SELF_CORNERS (a define of the host): the most corners a pass blends, 1
// in the vertex pass, so that it carries no corner blend (a software
// rasterizer would run it for every light).
#ifndef SELF_CORNERS
#define SELF_CORNERS 3
#endif
int g_self_corners = 0;
vec4 g_svdf_coefficients[SELF_CORNERS * MAX_STRIDE];
int g_corner_cluster[3];
float g_corner_weight[3];
LocalFrame g_corner_frame[3];

// Corner `corner`'s CPCA coefficients: those of the part's vertex `local_vertex`.
void load_svdf_coefficients(vec4 svdf, int local_vertex, int corner) {
    int stride = SVDF_STRIDE > 0 ? SVDF_STRIDE : int(svdf.w);
    for (int t = 0; t < stride; ++t)
        g_svdf_coefficients[corner * MAX_STRIDE + t] = fetch(u_svdf_coefficients, int(svdf.y) + local_vertex * stride + t);
}

// Corner `corner`'s reconstructed SVDF distance at plane point p.
float svdf_distance(vec4 svdf, int cluster, vec2 p, int corner) {
    int n = int(svdf.z), stride = SVDF_STRIDE > 0 ? SVDF_STRIDE : int(svdf.w), dims = n * n;
    BilinearTaps taps = bilinear_taps(n, p);
    float d = 0.0f;
    for (int k = 0; k < 4; ++k) {
        int row = int(svdf.x) + (cluster * dims + taps.index[k]) * stride;
        float value = 0.0f;
        for (int t = 0; t < stride; ++t)
            value += dot(fetch(u_svdf_tables, row + t), g_svdf_coefficients[corner * MAX_STRIDE + t]);
        d += taps.weight[k] * value;
    }
    return d;
}

// An OVDF row reconstruction Σ_t dot(row_t, w_t) at table texel `texel`.
float ovdf_row(int tables, int stride, int dims, int segment, int texel, vec4 w[MAX_STRIDE]) {
    int row = tables + (segment * dims + texel) * stride;
    float value = 0.0;
    for (int t = 0; t < stride; ++t) value += dot(fetch(u_ovdf_tables, row + t), w[t]);
    return value;
}

// The light-independent half of an OVDF lookup at a receiver point in the
// occluder's frame (OvdfLookup::locate): where the point lies among the
// shells and cube samples, whether it is inside the part, and the samples'
// blended occluded area. The vertex pass locates each (vertex, occluder)
// once for all its lights.
const int kOvdfOutside = 0;  // beyond the outer shell: 1 for every light
const int kOvdfInside = 1;   // inside the part: 0 for every light
const int kOvdfLocated = 2;
struct OvdfReceiver {
    int kind;
    vec3 dir;     // unit, from the part's center to the point
    float cone;   // the part's bounding cone seen from the point (plane radius)
    int s0;       // the shells s0, s0 + 1 and the weight of the upper one
    float fs;
    CubeFace face;
    SampleTaps at;
    float occluded_area;  // Ovdf::occluded_area_at: the bound of ovdf_area_bound
};

OvdfReceiver ovdf_locate(int part, vec3 point) {
    OvdfReceiver r;
    r.kind = kOvdfOutside;
    vec4 center = part_texel(part, kSlotOvdfCenter);
    vec4 bases = part_texel(part, kSlotOvdfBases);
    vec3 v = point - center.xyz;
    float d = length(v);
    if (d >= bases.w) return r;
    r.dir = d > 0.0f ? v / d : vec3(0.0f, 0.0f, 1.0f);
    r.cone = ovdf_zoom(d, center.w).cone;
    vec4 shells = part_texel(part, kSlotOvdfShells);
    vec4 grid = part_texel(part, kSlotOvdfGrid);
    vec4 records = part_texel(part, kSlotOvdfRecords);
    int shell_count = int(shells.x), n = int(grid.x);
    LerpPair pair = ovdf_shell_pair(
        ovdf_shell_coordinate(int(shells.y), shell_count, shells.z, shells.w, d / center.w), shell_count);
    r.s0 = pair.lower;
    r.fs = pair.upper_weight;
    r.face = cube_face(r.dir, u_face_normal);
    r.at = ovdf_sample_taps(r.dir, r.face.cosine, u_face_s[r.face.face], u_face_t[r.face.face], n);
    // A receiver inside the part sees nothing (Ovdf::receiver_inside): its
    // radial span decides where it can, else the samples' blended surface
    // distance (Ovdf::surface_distance_at).
    int span_inside = -1;
    int span_resolution = int(records.w);
    if (d < center.w && span_resolution > 0 && d > 0.0f) {
        SpanTaps span_taps = ovdf_span_taps(v, span_resolution);
        vec2 span = vec2(0.0f);
        for (int q = 0; q < 4; ++q) {
            int line = span_taps.index[q];
            vec4 texel = fetch(u_ovdf_frames, int(records.z) + line / 2);
            span += span_taps.weight[q] * ((line & 1) == 0 ? texel.xy : texel.zw);
        }
        span_inside = ovdf_span_inside(d, span, center.w);
    }
    r.kind = kOvdfInside;
    if (span_inside == 1) return r;
    // The samples' blended surface distance and occluded area.
    int surface_base = int(records.y);
    float surface = 0.0f;
    r.occluded_area = 0.0f;
    for (int k = 0; k < 2; ++k) {
        float ws = k == 0 ? 1.0f - r.fs : r.fs;
        if (ws == 0.0f) continue;
        vec2 value = vec2(0.0f);
        for (int q = 0; q < 4; ++q) {
            int sample_at = ovdf_sample_index(r.s0 + k, r.face.face, r.at.i[q], r.at.j[q], n);
            vec4 texel = fetch(u_ovdf_frames, surface_base + sample_at / kSamplesPerTexel);
            value += r.at.weight[q] * ((sample_at % kSamplesPerTexel) == 0 ? texel.xy : texel.zw);
        }
        surface += ws * value.x;
        r.occluded_area += ws * value.y;
    }
    if (d < center.w && span_inside < 0 && ovdf_inside_part(center.w, surface)) return r;
    r.kind = kOvdfLocated;
    return r;
}

// The light's half (OvdfLookup::visible_fraction, ovdf_receiver_fraction
// below) for a unit light in the occluder's frame and a square of half-edge
// h: the small-occluder rule where the square is wider than the part's
// cone, else the tables. In two halves for the vertex pass, which reads the
// tables only for the lights that need them: the small-occluder rule of a
// located receiver, for a part narrower than the square (weight > 0; it
// needs neither the pole frame nor the tables; the light's radius from the
// pole as the CPU's OvdfLookup takes it), then the tables faded into it
// (weight < 1).
struct OvdfSmall {
    float weight;
    float fraction;
};
OvdfSmall ovdf_receiver_small(OvdfReceiver r, vec3 light, float h) {
    OvdfSmall small;
    small.weight = ovdf_small_occluder_weight(r.cone, h, r.occluded_area);
    small.fraction = small.weight > 0.0f ? ovdf_small_occluder_fraction(ovdf_pole_radial(dot(light, normalize(-r.dir))),
                                                                          r.occluded_area, r.cone, h)
                                         : 1.0f;
    return small;
}

// The tables' half (OvdfLookup::visible_fraction past the small-occluder
// rule) of a located receiver, faded into `small`.
float ovdf_receiver_tables(int part, OvdfReceiver r, vec3 light, float h, OvdfSmall small) {
    vec4 bases = part_texel(part, kSlotOvdfBases);
    vec4 grid = part_texel(part, kSlotOvdfGrid);
    vec4 records = part_texel(part, kSlotOvdfRecords);
    int n = int(grid.x), vdt_n = int(grid.y), stride = OVDF_STRIDE > 0 ? OVDF_STRIDE : int(grid.z), m = int(grid.w);
    int tables = int(bases.x), coefficients = int(bases.y), dims = vdt_n * vdt_n;
    // The receiver's own pole frame, twisted by the face rule like its
    // samples: one plane point for all eight samples.
    vec2 lp = lookup_plane_point(frame_to_local(frame_from_normal_tangent(-r.dir, u_face_s[r.face.face]), light));
    float radial = length(lp);
    float distance = 0.0f;
    for (int k = 0; k < 2; ++k) {
        int shell = r.s0 + k;
        float ws = k == 0 ? 1.0f - r.fs : r.fs;
        if (ws == 0.0f) continue;
        // The shell's zoomed table (OvdfZoom), one record per shell.
        vec4 record = fetch(u_ovdf_frames, int(records.x) + shell);
        OvdfZoom zoom;
        zoom.zoom = record.x;
        zoom.cone = record.y;
        BilinearTaps taps = bilinear_taps(vdt_n, zoom.zoom * lp);
        // Reconstruction is linear in the coefficients: where the four
        // samples share a segment, blend them and reconstruct once; where
        // they straddle segments, reconstruct each sample's. One loop for
        // both (a software rasterizer runs both sides of a branch).
        int segment = ovdf_segment_of(shell, r.face.face, r.at.i[0], r.at.j[0], n, m);
        bool shared_segment = segment == ovdf_segment_of(shell, r.face.face, r.at.i[3], r.at.j[3], n, m);
        float value = 0.0f;  // × ws, table units
        for (int q = 0; q < (shared_segment ? 1 : 4); ++q) {
            // Shared: the four samples, blended; else sample q alone.
            int first = shared_segment ? 0 : q, last = shared_segment ? 4 : q + 1;
            vec4 c[MAX_STRIDE];
            for (int t = 0; t < stride; ++t) c[t] = vec4(0.0f);
            for (int k = first; k < last; ++k) {
                float weight = shared_segment ? r.at.weight[k] : 1.0f;
                int sample_at = ovdf_sample_index(shell, r.face.face, r.at.i[k], r.at.j[k], n);
                for (int t = 0; t < stride; ++t)
                    c[t] += weight * fetch(u_ovdf_coefficients, coefficients + sample_at * stride + t);
            }
            if (shared_segment) c[0].x = 1.0f;  // the mean's weight (the blend weights sum to 1)
            int segment_at =
                shared_segment ? segment : ovdf_segment_of(shell, r.face.face, r.at.i[q], r.at.j[q], n, m);
            float reconstructed = 0.0f;
            for (int t = 0; t < 4; ++t)
                reconstructed += taps.weight[t] * ovdf_row(tables, stride, dims, segment_at, taps.index[t], c);
            value += shared_segment ? reconstructed : r.at.weight[q] * reconstructed;
        }
        distance += ovdf_weighted_plane_distance(ws * value, ws, zoom, radial);
    }
    float by_tables = ovdf_area_bound(visible_fraction_from_distance(ovdf_receiver_distance(distance, radial, r.cone), h),
                                      r.occluded_area, h);
    return ovdf_fade_small_occluder(by_tables, small.fraction, small.weight);
}

float ovdf_receiver_fraction(int part, OvdfReceiver r, vec3 light, float h) {
    if (r.kind == kOvdfOutside) return 1.0f;
    if (r.kind == kOvdfInside) return 0.0f;
    OvdfSmall small = ovdf_receiver_small(r, light, h);
    if (small.weight >= 1.0f) return small.fraction;
    return ovdf_receiver_tables(part, r, light, h, small);
}

// Ovdf::visible_fraction (AlignedCoefficients) as OvdfLookup computes it:
// point and unit light in the occluder's frame; the per-pixel pass's lookup.
float ovdf_visible_fraction(int part, vec3 point, vec3 light, float h) {
    vec4 center = part_texel(part, kSlotOvdfCenter);
    vec3 v = point - center.xyz;
    float d = length(v);
    if (d >= part_texel(part, kSlotOvdfBases).w) return 1.0f;
    // The receiver's own bounding cone (the CPU's per-vertex test,
    // OvdfLookup::unshadowed): the lookup gives 1 beyond it.
    vec3 dir = d > 0.0f ? v / d : vec3(0.0f, 0.0f, 1.0f);
    if (ovdf_unshadowed(dot(light, -dir), ovdf_zoom(d, center.w).cone, h)) return 1.0f;
    return ovdf_receiver_fraction(part, ovdf_locate(part, point), light, h);
}

// The exact shadow of a part that is a rectangle or a box
// (shape_visible_fraction): shape = (center, kind), point in the part's
// frame, `axes` the receiver's shading frame and `linear` the part's inverse
// transform that moves it there.
float exact_shape_fraction(int part, vec4 shape, vec3 point, LocalFrame axes, mat3 linear, vec2 lp, float h) {
    // Within the field's reach only, as its lookup and the occluder lists.
    vec4 field = part_texel(part, kSlotOvdfCenter);
    if (!(length(point - field.xyz) < field.w * part_texel(part, kSlotOvdfShells).w)) return 1.0;
    mat3 to_shape = transpose(mat3(part_texel(part, kSlotShapeS).xyz, part_texel(part, kSlotShapeT).xyz,
                                   part_texel(part, kSlotShapeNormal).xyz));
    LocalFrame frame;
    frame.x = to_shape * (linear * axes.x);
    frame.y = to_shape * (linear * axes.y);
    frame.z = to_shape * (linear * axes.z);
    return shape_visible_fraction(int(shape.w + 0.5), to_shape * (point - shape.xyz), frame, lp, h,
                                  part_texel(part, kSlotShapeLow).xyz, part_texel(part, kSlotShapeHigh).xyz);
}

// The slab rule (clears_box_face_scaled): point in the part's frame, light =
// inverse_linear·(world direction), not normalized; the face normals are the
// rows of inverse_linear.
bool clears_box(int part, vec3 point, vec3 light, mat3 inverse_linear, float h) {
    vec3 sides = box_sides(part_texel(part, kSlotBoxLow).xyz, part_texel(part, kSlotBoxHigh).xyz, point);
    mat3 rows = transpose(inverse_linear);
    vec3 face_scale = vec3(length(rows[0]), length(rows[1]), length(rows[2]));
    return clears_box_face_scaled(sides, light, face_scale, square_cone_sine(h));
}

// ---- the shadow-mapped baseline (shading_core.h "shadow maps") ----

// Lit fraction of environment light `layer` (centre direction L) over its
// square (plane centre lp, half-edge h) at world point p, shading frame
// `frame` (columns x, y, z = normal). The taps are the square's own
// directions (shadow_tap_point) above the horizon; a ray along one reaches
// the blockers' depth at `distance` × its slope across the map. PCF assumes
// the distance (u_pcf_depth); PCSS searches blockers and takes their mean
// distance (blocker_distance). Each texel a tap reads is compared with the
// receiver's own tangent plane at the texel's centre (the receiver-plane
// depth bias), less a constant bias.
struct ShadowReceiver {
    vec3 q;         // the receiver in the map: (u, v, depth)
    vec2 gradient;  // its tangent plane's depth per unit map offset
    float bias;     // depth units
    int layer;
};
vec2 g_shadow_slope[kShadowTaps];

// Texel t of the receiver's map: 1 (nothing in front) outside it.
float shadow_depth(ShadowReceiver r, ivec2 t) {
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(u_shadow_resolution)))) return 1.0;
    return texelFetch(u_shadow_depths, ivec3(t, r.layer), 0).r;
}
// The receiver's tangent plane at texel t's centre: a texel nearer than
// this less the bias blocks.
float shadow_plane(ShadowReceiver r, ivec2 t) {
    vec2 center = (vec2(t) + 0.5) * u_shadow_texel;
    return r.q.z + dot(center - r.q.xy, r.gradient);
}
// Lit share at map point uv, bilinear over the four nearest texels.
float shadow_lit(ShadowReceiver r, vec2 uv) {
    vec2 t = uv * float(u_shadow_resolution) - 0.5;
    vec2 base = floor(t);
    vec2 f = t - base;
    float lit = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 texel = ivec2(base) + ivec2(k & 1, k >> 1);
        float weight = ((k & 1) == 0 ? 1.0 - f.x : f.x) * ((k >> 1) == 0 ? 1.0 - f.y : f.y);
        if (shadow_depth(r, texel) >= shadow_plane(r, texel) - r.bias) lit += weight;
    }
    return lit;
}

// PCSS's blocker search: the mean distance (depth units) from the blockers
// that the taps at `distance` × slope find down to the receiver's tangent
// plane below each (not to the receiver itself: a blocker plane tilted
// against the light, found far to the side, would read as near), or 0 when
// they find none.
float blocker_distance(ShadowReceiver r, int taps, float distance) {
    float sum = 0.0;
    int blockers = 0;
    for (int k = 0; k < taps; ++k) {
        ivec2 texel = ivec2(floor((r.q.xy + distance * g_shadow_slope[k]) * float(u_shadow_resolution)));
        float depth = shadow_depth(r, texel), plane = shadow_plane(r, texel);
        if (depth < plane - r.bias) {
            sum += plane - depth;
            ++blockers;
        }
    }
    return blockers == 0 ? 0.0 : sum / float(blockers);
}

float shadow_visible_fraction(int layer, vec3 light, vec3 p, LocalFrame frame, vec2 lp, float h) {
    LocalFrame m = shadow_map_frame(light);
    ShadowReceiver r;
    r.q = shadow_map_point(m, u_shadow_sphere.xyz, u_shadow_sphere.w, p);
    r.gradient = shadow_receiver_gradient(m, frame.z);
    r.bias = kShadowDepthBiasTexels * u_shadow_texel;
    r.layer = layer;
    int taps = 0;
    for (int i = 0; i < kShadowTaps; ++i) {
        vec2 point = shadow_tap_point(lp, h, i);
        if (dot(point, point) >= 1.0) continue;  // below the horizon: the BRDF average is 0 there
        g_shadow_slope[taps++] = shadow_map_slope(m, frame_to_world(frame, plane_to_hemisphere(point)));
    }
    if (taps == 0) return 1.0;
    float distance = u_pcf_depth;
    if (u_shadow_pcss) {
        // Over the widest footprint: rays up to the map's near face (depth 0).
        distance = blocker_distance(r, taps, r.q.z);
        if (distance == 0.0) return 1.0;
    }
    float lit = 0.0;
    for (int k = 0; k < taps; ++k) lit += shadow_lit(r, r.q.xy + distance * g_shadow_slope[k]);
    return lit / float(taps);
}

// ---- the sum ----

// Light l at world point p: its direction, square half-edge and integral;
// a sphere light that contains p has h = 0 (no share).
struct PointLight {
    vec3 direction;
    float h;
    vec3 integral;
};
PointLight light_at(int l, vec3 p) {
    vec4 a = fetch(u_lights, kLightTexels * l), b = fetch(u_lights, kLightTexels * l + 1);
    PointLight light;  // an environment square: direction, half-edge, 2r²·I
    light.direction = a.xyz;
    light.h = a.w;
    light.integral = b.rgb;
#if LOCAL_LIGHTS
    if (l >= u_environment_lights) {
        // A sphere light: center a.xyz, radius a.w, radiance b.rgb; spot axis c.xyz, cone (b.w, c.w).
        vec3 to_center = a.xyz - p;
        float distance = length(to_center);
        light.h = 0.0;
        light.integral = vec3(0.0);
        light.direction = vec3(0.0, 0.0, 1.0);
        if (!(distance > a.w)) return light;
        light.direction = to_center / distance;
        float solid_angle = sphere_cap_solid_angle(a.w, distance);
        light.h = half_edge_for_solid_angle(solid_angle);
        vec4 c = fetch(u_lights, kLightTexels * l + 2);
        light.integral = b.rgb * (solid_angle * spot_cone_factor(c.xyz, -light.direction, b.w, c.w));
    }
#endif
    return light;
}

struct PointShade {
    vec3 color;     // the diffuse sum at unit texture (textured parts), else the whole sum
    vec3 specular;  // textured parts (kSlotSpecular.w = 1): the specular table's sum
};

// Self-visibility of the light with direction `direction`, plane point lp in
// the point's frame and half-edge h (g_self_corners).
float self_visibility(vec4 svdf, vec3 direction, vec2 lp, float h) {
    if (g_self_corners == 0) return 1.0;
#if SELF_CORNERS == 1
    return visible_fraction_from_distance(svdf_distance(svdf, g_corner_cluster[0], lp, 0), h);
#else
    if (g_self_corners == 1) return visible_fraction_from_distance(svdf_distance(svdf, g_corner_cluster[0], lp, 0), h);
    float blend = 0.0;
    for (int c = 0; c < 3; ++c) {
        // A corner whose hemisphere the square misses has no share (the
        // CPU's vertex pass queries no such square).
        vec3 local = frame_to_local(g_corner_frame[c], direction);
        if (!square_reaches_hemisphere(local.z, h)) continue;
        float corner = g_corner_cluster[c] < 0
                           ? 1.0
                           : visible_fraction_from_distance(
                                 svdf_distance(svdf, g_corner_cluster[c], hemisphere_to_plane(local), c), h);
        blend += g_corner_weight[c] * corner;
    }
    return blend;
#endif
}

// The sum at world point p of `part`, shading frame `frame` (rows: tangent,
// bitangent, normal: frame_from_normal_tangent), towards u_camera, with self_visibility's factor.
PointShade shade_point(int part, vec3 p, LocalFrame frame) {
    vec4 material = part_texel(part, kSlotMaterial);
    vec4 specular_material = part_texel(part, kSlotSpecular);
    bool layered = specular_material.w > 0.5;
    vec4 svdf = part_texel(part, kSlotSvdf);
    bool isotropic = material.y > 0.5;
    vec3 wo = frame_to_local(frame, normalize(u_camera - p));
    vec2 alignment = view_alignment(wo);

    PointShade result;
    result.color = vec3(0.0);
    result.specular = vec3(0.0);
    if (!(wo.z > 0.0)) return result;
    int first = u_environment_enabled ? 0 : u_environment_lights;
    int last = u_local_enabled ? u_light_count : u_environment_lights;
    for (int l = first; l < last; ++l) {
        PointLight light = light_at(l, p);
        vec3 direction = light.direction;
        float h = light.h;
        vec3 integral = light.integral;
        vec3 local = frame_to_local(frame, direction);
        vec2 lp = hemisphere_to_plane(local);
        if (!(h > 0.0f) || !square_reaches_hemisphere(local.z, h)) continue;
        vec2 square = isotropic ? to_view_aligned(lp, alignment) : lp;
        vec3 brdf = brdf_average(material, square, h, wo);
        vec3 specular_brdf = layered ? brdf_average(specular_material, square, h, wo) : vec3(0.0);
        if (u_shadow_maps && l < u_environment_lights) {  // the baseline's visibility, in place of the fields'
            float lit = shadow_visible_fraction(l, direction, p, frame, lp, h);
            result.color += integral * brdf * lit;
            result.specular += integral * specular_brdf * lit;
            continue;
        }
        float visibility = self_visibility(svdf, direction, lp, h);
        int slot = part * u_light_count + l;
        int list_end = int(list_texel(slot + 1));
        for (int e = int(list_texel(slot)); e < list_end; ++e) {
            if (!(visibility > 0.0)) break;
            int o = int(list_texel(e));
            mat4 inverse = mat4(part_texel(o, kSlotInverse), part_texel(o, kSlotInverse + 1),
                                part_texel(o, kSlotInverse + 2), part_texel(o, kSlotInverse + 3));
            vec3 point = (inverse * vec4(p, 1.0)).xyz;
            vec3 dir = normalize(mat3(inverse) * direction);
            if (clears_box(o, point, mat3(inverse) * direction, mat3(inverse), h)) continue;
            vec4 shape = part_texel(o, kSlotShape);
            visibility *= shape.w > 0.5 ? exact_shape_fraction(o, shape, point, frame, mat3(inverse), lp, h)
                                        : ovdf_visible_fraction(o, point, dir, h);
        }
        result.color += integral * brdf * visibility;
        result.specular += integral * specular_brdf * visibility;
    }
    return result;
}
