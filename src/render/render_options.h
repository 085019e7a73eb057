#pragma once
// What every runtime renderer computes and which approximations it uses
// (docs/design/RENDERER.md), whichever backend runs the sum; the few options
// of one backend say so. Every toggle exists so that one factor of the
// product can be switched off and measured against the ground truth.
#include <map>
#include <memory>
#include <string>

#include "src/brdf/brdf_table.h"

namespace rsl {

class ExactVisibility;  // src/render/exact_visibility.h

// A competitor baseline, GL backend only (docs/design/GPU_DESIGN.md, "Shadow-mapped
// visibility"): every environment RSL's visibility factor (what replaces
// SVDF × Π OVDF) comes from an orthographic depth map along the light's
// centre, filtered over the light's square; local lights keep the fields.
// The CPU renderer refuses it (rsl::Error).
enum class ShadowFilter {
    Pcf,   // fixed blocker distance: pcf_distance × the scene's bounding radius
    Pcss,  // blocker search, then the kernel of the blocker's mean distance
};
struct ShadowMapOptions {
    static constexpr int kMinResolution = 16, kMaxResolution = 8192;
    bool enabled = false;
    int resolution = 1024;  // texels per side of each light's map (depth32F: 4·res² bytes per light)
    ShadowFilter filter = ShadowFilter::Pcss;
    float pcf_distance = 0.1f;  // Pcf only: the occluder distance the kernel assumes, × the bounding radius
};

// A competitor baseline, GL backend only (docs/design/GPU_DESIGN.md,
// "Ray-traced visibility"): every light's visibility (what replaces SVDF ×
// Π OVDF) from S×S jittered shadow rays per vertex and light, traced in the
// vertex pass through a BVH of the posed parts: the rays of the CPU's
// ray-traced rows (exact_visibility, jittered), from the same seeds. The
// CPU renderer refuses it (it has exact_visibility).
struct GpuRayOptions {
    static constexpr int kMaxSamplesPerSide = 16;
    bool enabled = false;
    int samples_per_side = 1;  // S
};

enum class PixelShadows { Off, Planes, All };
// "off", "planes" or "all" (the command line's and the API's words); others throw rsl::Error.
PixelShadows parse_pixel_shadows(const std::string& name);

struct RenderOptions {
    int environment_light_count = 30;  // K: RSLs fitted to the environment map
    bool cross_face_lights = true;   // fit regions across cube-face borders (docs/design/LIGHTFIT.md)
    bool environment = true;         // shade with the environment's RSLs
    bool local_lights = true;        // shade with the scene's sphere lights
    bool self_visibility = true;     // multiply by the SVDF average
    bool occluders = true;           // multiply by the other parts' OVDF averages
    // Shade each BRDF's constant (diffuse) term with the environment's exact
    // irradiance, the squares giving its shadows as a ratio (docs/design/RENDERER.md
    // "Exact diffuse light"); off: the squares' own light, as the RSL paper.
    bool exact_diffuse_light = true;
    bool occluder_culling = true;    // skip occluders that cannot shadow (never changes the result)
    // OVDF lookups split into a per-(vertex, occluder) half and a per-light half
    // (src/render/ovdf_lookup.h; same values as the field's own lookup, faster).
    bool fast_occluder_lookups = true;
    // Parts that are a flat rectangle (a ground, a wall) or a box shadow the
    // others exactly, from their shape, in place of their OVDF
    // (src/render/occluder_shape.h). On by default: near a ground or a box
    // the OVDF blends samples from both sides of a face (15-30% dark on a
    // box resting on the ground); the taps cost the bunny and the robot about
    // 5% of their frame (docs/design/RENDERER.md).
    bool exact_shapes = true;
    // Sharp shadows on coarse receivers (docs/design/RENDERER.md "Per-pixel
    // shadows"): in images, the parts shaded per pixel take the other parts'
    // occluder factor at each pixel's point, on the triangles where it
    // differs between the corners (elsewhere, and per vertex, nothing
    // changes). Planes: the parts that are one flat rectangle (grounds,
    // floors, walls); All: every part. CPU backend.
    PixelShadows pixel_shadows = PixelShadows::Planes;
    // View-dependent highlights between vertices: in images, glossy parts
    // (every material but Lambert; untextured) take the BRDF average of each
    // light at each pixel's own normal and view, with the vertices' SVDF and
    // occluder factors blended (docs/design/RENDERER.md "Per-pixel highlights").
    bool pixel_highlights = true;
    // Per-part material override: part name → material name (scene materials).
    std::map<std::string, std::string> material_override;
    BrdfTableOptions brdf_table;     // resolution of the BRDF summed-area tables
    // Diagnostic: ray-traced visibility in place of the SVDF, the OVDFs or both
    // (its mode says which); it must be posed at the renderer's time.
    std::shared_ptr<const ExactVisibility> exact_visibility;
    ShadowMapOptions shadow_maps;  // GL backend only
    GpuRayOptions gpu_rays;        // GL backend only
    // The rays backend's S (src/render/ray_traced_renderer.h): every light's
    // visibility from S×S jittered shadow rays per vertex, 1 to
    // kMaxRaySamples; the other backends ignore it.
    static constexpr int kMaxRaySamples = 16;
    int ray_samples = 1;
};

// Counters of one shading pass (for `rsl render` and the benchmarks).
struct RenderStats {
    size_t vertices = 0;
    size_t lights = 0;                 // environment RSLs + local lights
    size_t lookups = 0;                // (vertex, light) pairs that reached the lookups
    size_t occluder_pairs = 0;         // (receiver part, occluder part, light) triples considered
    size_t occluder_pairs_culled = 0;  // ... of which culled
    size_t block_occluders_culled = 0; // (block, occluder, light) triples skipped by the block's bounding sphere
    size_t occluder_lookups = 0;       // OVDF lookups that ran (vertex, light, occluder)
    size_t shadow_rays = 0;            // rays traced by exact_visibility (the ray-traced baseline)
};

}  // namespace rsl
