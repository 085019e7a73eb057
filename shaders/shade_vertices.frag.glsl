#version 330 core
// The shading pass (RSL paper §5.2, Figure 8): one fragment per vertex of the
// vertex rectangle computes
//
//   Σ_lights  2r²·I  ×  BRDF-SAT average  ×  SVDF average  ×  Π_occluders OVDF average
//
// with the same arithmetic as the CPU renderer (src/render/shade_block.cpp,
// src/brdf/brdf_table.cpp, fields/svdf.h, fields/ovdf.cpp), so that the two
// agree to float rounding. Layout of every texture: src/gl/gpu_layout.h.
// Defines from the host: MAX_STRIDE (texels of a CPCA row).

const int kArrayWidth = 2048;  // gl_objects.h kArrayTextureWidth
const int kArrayShift = 11;
const float kSqrt2 = 1.41421356237;

uniform sampler2D u_positions;     // vertex rectangle: part-space position, part
uniform sampler2D u_normals;       // normal, SVDF cluster
uniform sampler2D u_tangents;      // tangent
uniform sampler2D u_parts;         // part records (kPartStride texels each)
uniform sampler2D u_lights;        // 2 texels per light
uniform usampler2D u_occluders;    // (light, part) → bit mask of occluder parts
uniform sampler3D u_brdf;          // SAT corners, slices stacked
uniform sampler2D u_brdf_offsets;  // per slice mean offset
uniform sampler2D u_svdf_tables;
uniform sampler2D u_svdf_coefficients;
uniform sampler2D u_ovdf_tables;
uniform sampler2D u_ovdf_coefficients;
uniform sampler2D u_ovdf_frames;
uniform sampler2D u_occluder_spheres;  // (receiver, occluder): grown world bounding sphere

uniform int u_vertex_count;
uniform int u_part_count;
uniform int u_environment_lights;  // lights [0, E) are environment squares, [E, L) local sphere lights
uniform int u_light_count;
uniform bool u_environment_enabled;  // RenderOptions::environment
uniform bool u_local_enabled;        // RenderOptions::local_lights
uniform int u_brdf_resolution;     // N
uniform vec3 u_camera;
uniform bool u_self_visibility;
uniform bool u_vertex_culling;     // per-vertex cone test (RenderOptions::occluder_culling)
uniform vec3 u_face_normal[6];
uniform vec3 u_face_s[6];
uniform vec3 u_face_t[6];

layout(location = 0) out vec4 o_color;

vec4 fetch(sampler2D array, int i) { return texelFetch(array, ivec2(i & (kArrayWidth - 1), i >> kArrayShift), 0); }
vec4 part_texel(int part, int slot) { return fetch(u_parts, part * 20 + slot); }  // kPartStride = 20

// ---- frames and the equal-area map (src/core/math.h, hemisphere.h) ----

vec3 any_orthonormal(vec3 n) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
}

// Frame::from_normal_tangent: rows x, y, z of the world → local rotation.
mat3 frame_rows(vec3 n, vec3 t) {
    vec3 z = normalize(n);
    vec3 x = t - z * dot(z, t);
    float len2 = dot(x, x);
    x = len2 > 1e-12 ? x / sqrt(len2) : any_orthonormal(z);
    return mat3(x, cross(z, x), z);  // columns; local = transpose(frame) * world
}
vec3 to_local(mat3 frame, vec3 v) { return vec3(dot(v, frame[0]), dot(v, frame[1]), dot(v, frame[2])); }

vec2 hemisphere_to_plane(vec3 w) { return w.xy * (1.0 / sqrt(max(1.0 + w.z, 1e-12))); }

// ---- BRDF summed-area tables (brdf_table.cpp) ----

struct Taps {
    ivec4 ax, by;
    vec4 wx, wy;
    float clipped_area, inv_full_area;
};

void bracket(float x, int n, out int lower, out float upper_weight) {
    lower = min(int(x), n - 1);
    upper_weight = x - float(lower);
}

Taps square_taps(vec2 c, float h) {
    int n = u_brdf_resolution;
    float scale = 0.5 * float(n);
    h = max(h, 1e-6);
    float x0 = clamp((c.x - h + 1.0) * scale, 0.0, float(n));
    float x1 = clamp((c.x + h + 1.0) * scale, 0.0, float(n));
    float y0 = clamp((c.y - h + 1.0) * scale, 0.0, float(n));
    float y1 = clamp((c.y + h + 1.0) * scale, 0.0, float(n));
    int a0, a1, b0, b1;
    float f0, f1, g0, g1;
    bracket(x0, n, a0, f0);
    bracket(x1, n, a1, f1);
    bracket(y0, n, b0, g0);
    bracket(y1, n, b1, g1);
    Taps t;
    t.ax = ivec4(a1, a1 + 1, a0, a0 + 1);
    t.wx = vec4(1.0 - f1, f1, f0 - 1.0, -f0);
    t.by = ivec4(b1, b1 + 1, b0, b0 + 1);
    t.wy = vec4(1.0 - g1, g1, g0 - 1.0, -g0);
    t.clipped_area = (x1 - x0) * (y1 - y0);
    float edge = 2.0 * h * scale;
    t.inv_full_area = 1.0 / (edge * edge);
    return t;
}

vec3 slice_integral(int s, Taps t) {
    vec3 sum = vec3(0.0);
    for (int n = 0; n < 4; ++n)
        for (int m = 0; m < 4; ++m) sum += (t.wx[m] * t.wy[n]) * texelFetch(u_brdf, ivec3(t.ax[m], t.by[n], s), 0).rgb;
    return sum + fetch(u_brdf_offsets, s).rgb * t.clipped_area;
}

void sample_lerp(float t, int v, out int k0, out float w) {
    t = clamp(t, 0.0, float(v - 1));
    k0 = min(int(t), v - 2);
    w = t - float(k0);
}

// Average of ρ·cos over the square (table frame) for view `view`; material =
// (first slice, isotropic, V, 0).
vec3 brdf_average(vec4 material, vec2 c, float h, vec3 view) {
    Taps t = square_taps(c, h);
    if (t.clipped_area <= 0.0) return vec3(0.0);
    int first = int(material.x), v = int(material.z);
    vec3 sum = vec3(0.0);
    if (material.y > 0.5) {
        int k0;
        float w;
        sample_lerp(sqrt(clamp(1.0 - view.z, 0.0, 1.0)) * float(v) - 0.5, v, k0, w);
        sum += (1.0 - w) * slice_integral(first + k0, t);
        sum += w * slice_integral(first + k0 + 1, t);
    } else {
        vec2 p = hemisphere_to_plane(vec3(view.xy, max(view.z, -0.999)));
        float len2 = dot(p, p);
        if (len2 > 1.0) p /= sqrt(len2);
        int i0, j0;
        float wi, wj;
        sample_lerp((p.x + 1.0) * 0.5 * float(v) - 0.5, v, i0, wi);
        sample_lerp((p.y + 1.0) * 0.5 * float(v) - 0.5, v, j0, wj);
        int s = first + j0 * v + i0;
        sum += ((1.0 - wi) * (1.0 - wj)) * slice_integral(s, t);
        sum += (wi * (1.0 - wj)) * slice_integral(s + 1, t);
        sum += ((1.0 - wi) * wj) * slice_integral(s + v, t);
        sum += (wi * wj) * slice_integral(s + v + 1, t);
    }
    return sum * t.inv_full_area;
}

// ---- visibility distance tables (fields/vdt.h, svdf.h, ovdf.cpp) ----

float visible_fraction_from_distance(float d, float h) { return clamp(0.5 + d / (2.0 * h), 0.0, 1.0); }

// Bilinear taps between texel centers of an n×n table (vdt.cpp bilinear_taps).
void bilinear_taps(int n, vec2 p, out ivec4 index, out vec4 weight) {
    float hi = float(n - 1);
    float u = clamp((p.x + 1.0) * (0.5 * float(n)) - 0.5, 0.0, hi);
    float v = clamp((p.y + 1.0) * (0.5 * float(n)) - 0.5, 0.0, hi);
    int i0 = min(int(u), n - 2), j0 = min(int(v), n - 2);
    float fx = u - float(i0), fy = v - float(j0);
    int base = j0 * n + i0;
    index = ivec4(base, base + 1, base + n, base + n + 1);
    weight = vec4((1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy);
}

vec4 g_svdf_coefficients[MAX_STRIDE];

// The vertex's reconstructed SVDF distance at plane point p.
float svdf_distance(vec4 svdf, int cluster, vec2 p) {
    int n = int(svdf.z), stride = int(svdf.w), dims = n * n;
    ivec4 index;
    vec4 weight;
    bilinear_taps(n, p, index, weight);
    float d = 0.0;
    for (int k = 0; k < 4; ++k) {
        int row = int(svdf.x) + (cluster * dims + index[k]) * stride;
        float value = 0.0;
        for (int t = 0; t < stride; ++t) value += dot(fetch(u_svdf_tables, row + t), g_svdf_coefficients[t]);
        d += weight[k] * value;
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

float shell_coordinate(vec4 shells, float distance, float radius) {
    float d = distance / radius, last = shells.x - 1.0, inner = shells.z, outer = shells.w;
    int spacing = int(shells.y);
    if (spacing == 0) return last * log(max(d, 1e-6) / inner) / log(outer / inner);
    if (spacing == 1) return last * (d - inner) / (outer - inner);
    return last * (1.0 / max(d, 1e-6) - 1.0 / inner) / (1.0 / outer - 1.0 / inner);
}

// Ovdf::visible_fraction (AlignedCoefficients): point and light in the occluder's frame.
float ovdf_visible_fraction(int part, vec3 point, vec3 light, float h) {
    vec4 center = part_texel(part, 14);
    vec4 bases = part_texel(part, 15);
    vec3 v = point - center.xyz;
    float d = length(v);
    if (d >= bases.w) return 1.0;
    vec4 shells = part_texel(part, 16);
    vec4 grid = part_texel(part, 17);
    vec3 dir = d > 0.0 ? v / d : vec3(0.0, 0.0, 1.0);
    // The part lies in its bounding cone seen from the point (ovdf_zoom's
    // cone, Ovdf::distance's last bound): lights beyond it are unshadowed.
    // √2·sin(½·asin x) without the driver's asin/sin approximations (ovdf_zoom).
    float sin_cone = center.w / d;
    float cone = d > center.w ? sin_cone / sqrt(1.0 + sqrt(1.0 - sin_cone * sin_cone)) : 1e6;
    float limit = h + cone;
    if (dot(light, -dir) <= 1.0 - limit * limit) return 1.0;
    int shell_count = int(shells.x), n = int(grid.x), vdt_n = int(grid.y), stride = int(grid.z), m = int(grid.w);
    float u = clamp(shell_coordinate(shells, d, center.w), 0.0, float(shell_count - 1));
    int s0 = min(int(u), shell_count - 2);
    float fs = u - float(s0);
    int face = 0;
    float best = -2.0;
    for (int f = 0; f < 6; ++f) {
        float c = dot(dir, u_face_normal[f]);
        if (c > best) {
            best = c;
            face = f;
        }
    }
    float x = clamp((dot(dir, u_face_s[face]) / best + 1.0) * 0.5 * float(n) - 0.5, 0.0, float(n - 1));
    float y = clamp((dot(dir, u_face_t[face]) / best + 1.0) * 0.5 * float(n) - 0.5, 0.0, float(n - 1));
    int i0 = min(int(x), n - 2), j0 = min(int(y), n - 2);
    float fx = x - float(i0), fy = y - float(j0);
    ivec4 ii = ivec4(i0, i0 + 1, i0, i0 + 1), jj = ivec4(j0, j0, j0 + 1, j0 + 1);
    vec4 w = vec4((1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy);
    int tables = int(bases.x), coefficients = int(bases.y), dims = vdt_n * vdt_n;
    // A receiver inside the part (its samples' blended surface distance is
    // negative; Ovdf::surface_distance_at) sees nothing.
    int surface_base = int(bases.z) + 12 * n * n + shell_count;
    float surface = 0.0;
    for (int k = 0; k < 2 && d < center.w; ++k) {
        float ws = k == 0 ? 1.0 - fs : fs;
        if (ws == 0.0) continue;
        float value = 0.0;
        for (int q = 0; q < 4; ++q) {
            int sample = (((s0 + k) * 6 + face) * n + jj[q]) * n + ii[q];
            value += w[q] * fetch(u_ovdf_frames, surface_base + sample / 4)[sample % 4];
        }
        surface += ws * value;
    }
    if (d < center.w && surface < 0.0) return 0.0;
    // The receiver's own pole frame, twisted by the face rule like its
    // samples (OvdfBlend::AlignedCoefficients, the CPU's default): one
    // plane point for all eight samples.
    vec3 local = to_local(frame_rows(-dir, u_face_s[face]), light);
    vec2 lp = local.z < -0.9999 ? vec2(1.5) : hemisphere_to_plane(local);  // lookup_plane_point
    float radial = length(lp);
    float distance = 0.0;
    for (int k = 0; k < 2; ++k) {
        int shell = s0 + k;
        float ws = k == 0 ? 1.0 - fs : fs;
        if (ws == 0.0) continue;
        // The shell's zoomed table (fields/ovdf.h OvdfZoom): (zoom, cone), after the frames.
        vec2 zoom = fetch(u_ovdf_frames, int(bases.z) + 12 * n * n + shell).xy;
        ivec4 index;
        vec4 weight;
        bilinear_taps(vdt_n, zoom.x * lp, index, weight);
        int base = (shell * 6 + face) * m;
        int segment = (base + jj[0] * m / n) * m + ii[0] * m / n;
        if (segment == (base + jj[3] * m / n) * m + ii[3] * m / n) {
            // Reconstruction is linear in the coefficients: blend them first.
            vec4 c[MAX_STRIDE];
            for (int t = 0; t < stride; ++t) c[t] = vec4(0.0);
            for (int q = 0; q < 4; ++q) {
                int sample = ((shell * 6 + face) * n + jj[q]) * n + ii[q];
                for (int t = 0; t < stride; ++t) c[t] += w[q] * fetch(u_ovdf_coefficients, coefficients + sample * stride + t);
            }
            c[0].x = 1.0;  // the mean's weight (the blend weights sum to 1)
            float value = 0.0;
            for (int t = 0; t < 4; ++t) value += weight[t] * ovdf_row(tables, stride, dims, segment, index[t], c);
            distance += ws * max(value / zoom.x, radial - zoom.y);  // ovdf_plane_distance
        } else {  // the four samples straddle segments: four reconstructions
            float blended = 0.0;
            for (int q = 0; q < 4; ++q) {
                if (w[q] == 0.0) continue;
                int sample = ((shell * 6 + face) * n + jj[q]) * n + ii[q];
                int sample_segment = (base + jj[q] * m / n) * m + ii[q] * m / n;
                vec4 c[MAX_STRIDE];
                for (int t = 0; t < stride; ++t) c[t] = fetch(u_ovdf_coefficients, coefficients + sample * stride + t);
                float value = 0.0;
                for (int t = 0; t < 4; ++t) value += weight[t] * ovdf_row(tables, stride, dims, sample_segment, index[t], c);
                blended += w[q] * value;
            }
            distance += ws * max(blended / zoom.x, radial - zoom.y);
        }
    }
    return visible_fraction_from_distance(max(distance, radial - cone), h);
}

// The slab rule (src/render/square_lights.h clears_box_face): a receiver
// beyond a face of the occluder's bounding box is unshadowed by it when the
// light's square leaves that face's plane outwards. point: in the part's
// frame; light: inverse_linear·(world direction), not normalized, so that the
// test holds in the world for any scale (the face normals are the rows of
// inverse_linear).
float square_cone_sine(float h) {
    float rho_max = min(kSqrt2, 1.0 + kSqrt2 * h);
    float sin_half = rho_max / kSqrt2;
    float cos_half = sqrt(max(0.0, 1.0 - sin_half * sin_half));
    if (cos_half < 1e-3) return 2.0;
    float beta = min(3.14159265359, 2.0 * h / cos_half);
    return beta >= 0.5 * 3.14159265359 ? 2.0 : sin(beta);
}
bool clears_box_face(int part, vec3 point, vec3 light, mat3 inverse_linear, float h) {
    vec3 lo = part_texel(part, 18).xyz, hi = part_texel(part, 19).xyz;
    vec3 sides = vec3(greaterThan(point, hi)) - vec3(lessThan(point, lo));
    mat3 rows = transpose(inverse_linear);
    vec3 face_scale = vec3(length(rows[0]), length(rows[1]), length(rows[2]));
    vec3 s = sides * light / face_scale;
    return max(s.x, max(s.y, s.z)) >= square_cone_sine(h);
}

// Half-angle of a cone around the light's direction holding the part of its
// square above the horizon, for local z = lz (a bound for may_occlude, which
// the CPU renderer replaced by the exact cone test in the lookup itself).
float vertex_square_cone(float lz, float h) {
    float rho2 = min(2.0, max(1.0, 1.0 - lz));
    float denominator = sqrt(max(1e-12, 1.0 - 0.5 * rho2));
    return min(3.14159265359, 2.0 * h / denominator);
}

// Whether the light's cone (half-angle beta around `direction`) can meet the
// occluder's grown bounding sphere seen from p: the CPU renderer's per-vertex
// test, which never changes a result, only skips lookups that return 1.
bool may_occlude(int receiver, int occluder, vec3 p, vec3 direction, float beta) {
    vec4 sphere = fetch(u_occluder_spheres, receiver * u_part_count + occluder);
    vec3 to = sphere.xyz - p;
    float distance = length(to);
    float cone = distance > sphere.w ? asin(sphere.w / distance) : 3.14159265359;
    float reach = beta + cone;
    if (reach >= 3.14159265359) return true;
    vec3 u = distance > 0.0 ? to / distance : vec3(0.0, 0.0, 1.0);
    return dot(direction, u) >= cos(reach);
}

// ---- local lights (src/render/square_lights.h) ----

float sphere_cap_solid_angle(float radius, float distance) {
    float sin2 = min(1.0, (radius / distance) * (radius / distance));
    return 2.0 * 3.14159265359 * sin2 / (1.0 + sqrt(1.0 - sin2));
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    int vertex = texel.y * kArrayWidth + texel.x;
    if (vertex >= u_vertex_count) {
        o_color = vec4(0.0);
        return;
    }
    vec4 position = texelFetch(u_positions, texel, 0);
    vec4 normal = texelFetch(u_normals, texel, 0);
    vec3 tangent = texelFetch(u_tangents, texel, 0).xyz;
    int part = int(position.w);
    mat4 transform = mat4(part_texel(part, 0), part_texel(part, 1), part_texel(part, 2), part_texel(part, 3));
    mat3 normal_matrix = mat3(part_texel(part, 4).xyz, part_texel(part, 5).xyz, part_texel(part, 6).xyz);
    vec4 material = part_texel(part, 11);
    vec4 svdf = part_texel(part, 12);
    int local_vertex = vertex - int(part_texel(part, 13).x);
    bool isotropic = material.y > 0.5;

    vec3 p = (transform * vec4(position.xyz, 1.0)).xyz;
    mat3 frame = frame_rows(normalize(normal_matrix * normal.xyz), mat3(transform) * tangent);
    vec3 wo = to_local(frame, normalize(u_camera - p));
    float len2 = wo.x * wo.x + wo.y * wo.y;
    float inv = len2 > 1e-16 ? 1.0 / sqrt(len2) : 0.0;
    float view_cos = len2 > 1e-16 ? wo.y * inv : 1.0;
    float view_sin = wo.x * inv;

    bool self = u_self_visibility && svdf.z > 0.0 && normal.w >= 0.0;
    int cluster = int(normal.w);
    if (self) {
        int stride = int(svdf.w);
        for (int t = 0; t < stride; ++t)
            g_svdf_coefficients[t] = fetch(u_svdf_coefficients, int(svdf.y) + local_vertex * stride + t);
    }

    vec3 color = vec3(0.0);
    if (wo.z > 0.0) {
        int first = u_environment_enabled ? 0 : u_environment_lights;
        int last = u_local_enabled ? u_light_count : u_environment_lights;
        for (int l = first; l < last; ++l) {
            vec4 a = fetch(u_lights, 2 * l), b = fetch(u_lights, 2 * l + 1);
            vec3 direction;
            float h;
            vec3 integral;
            if (l < u_environment_lights) {
                direction = a.xyz;
                h = a.w;
                integral = b.rgb;
            } else {  // sphere light: center a.xyz, radius a.w, radiance b.rgb
                vec3 to_center = a.xyz - p;
                float distance = length(to_center);
                if (!(distance > a.w)) continue;
                direction = to_center / distance;
                float solid_angle = sphere_cap_solid_angle(a.w, distance);
                h = 0.5 * sqrt(0.5 * solid_angle);
                integral = b.rgb * solid_angle;
            }
            vec3 local = to_local(frame, direction);
            vec2 lp = local.xy * (1.0 / sqrt(max(1.0 + local.z, 1e-12)));
            float reach = 1.0 + kSqrt2 * h;
            if (!(h > 0.0) || !(local.z > 1.0 - reach * reach)) continue;
            vec3 brdf;
            if (isotropic) {
                vec2 tc = vec2(lp.x * view_cos - lp.y * view_sin, lp.x * view_sin + lp.y * view_cos);
                brdf = brdf_average(material, tc, h, wo);
            } else {
                brdf = brdf_average(material, lp, h, wo);
            }
            float visibility = self ? visible_fraction_from_distance(svdf_distance(svdf, cluster, lp), h) : 1.0;
            uint mask = texelFetch(u_occluders, ivec2(l, part), 0).r;
            float beta = u_vertex_culling ? vertex_square_cone(local.z, h) : 3.14159265359;
            for (int o = 0; o < u_part_count && mask != 0u; ++o) {
                if ((mask & (1u << uint(o))) == 0u) continue;
                mask &= ~(1u << uint(o));
                if (!(visibility > 0.0)) break;
                if (u_vertex_culling && !may_occlude(part, o, p, direction, beta)) continue;
                mat4 inverse = mat4(part_texel(o, 7), part_texel(o, 8), part_texel(o, 9), part_texel(o, 10));
                vec3 point = (inverse * vec4(p, 1.0)).xyz;
                vec3 dir = normalize(mat3(inverse) * direction);
                if (clears_box_face(o, point, mat3(inverse) * direction, mat3(inverse), h)) continue;
                visibility *= ovdf_visible_fraction(o, point, dir, h);
            }
            color += integral * brdf * visibility;
        }
    }
    o_color = vec4(color, 1.0);
}
