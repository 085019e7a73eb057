// The visibility fields at a point (docs/design/FIELDS.md): the SVDF's
// average over a light's square (src/fields/svdf.h), the OVDF's lookup in
// an occluder's frame (src/fields/ovdf.cpp: location, small-occluder rule,
// tables), the exact shapes of grounds and boxes (src/render/occluder_shape.h)
// and the box test, as the CPU computes them. After shading_data.glsl.

// ---- visibility distance tables (src/fields/visibility_distance_table.h, svdf.h, ovdf.cpp) ----

// The self-visibility point_sum.glsl multiplies each light by: g_self_corners
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

// The light's half (OvdfLookup::visible_fraction) for a unit light in the occluder's frame and a square of half-edge
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
