#pragma once
// The renderer base: what every runtime renderer does and holds, whatever
// runs the sum (the CPU renderer, src/render/cpu_renderer.h; the GL one,
// src/gl/gl_renderer.h). It owns the scene's state (options, environment
// and local lights, fields, materials, time, view, the frame of time t,
// statistics) and implements its setters once: pose the scene at a time,
// swap and edit materials, change the lighting. A backend implements only
// what differs: shade every vertex into VertexColors, form an image, and
// take a change to its device (the hooks below). `rsl render`, the API, the
// demos and the benchmarks hold a VertexRenderer from make_renderer
// (src/backend/make_renderer.h), so a new backend derives from this class
// and adds one case to that factory.
//
// Call order per frame: edits (materials, lights) at any time between
// frames, then set_time (or set_view), then shade. A material edit made
// through materials() builds that material's table at the edit; the next
// shade() takes it up: the renderer compares each material's revision() with
// the one it last used, and re-points its parts to (CPU) or re-uploads (GL)
// only the tables that changed.
#include <optional>
#include <string>
#include <vector>

#include "src/brdf/material_library.h"
#include "src/core/scene.h"
#include "src/render/frame_setup.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/image/image_formation.h"
#include "src/formats/vertex_colors.h"

namespace rsl {

class VertexRenderer {
public:
    virtual ~VertexRenderer() = default;
    // A backend's members refer to the frame and fields held here: neither copied nor moved.
    VertexRenderer(const VertexRenderer&) = delete;
    VertexRenderer& operator=(const VertexRenderer&) = delete;

    // "cpu", "gl": what `rsl render` prints and the .rslv producer says.
    virtual std::string backend() const = 0;
    // A line about where it runs ("GPU: EGL surfaceless: OpenGL 4.5 …"); the backend by default.
    virtual std::string device() const { return backend(); }
    // The scene it renders (it must outlive the renderer), and its options.
    const Scene& scene() const { return scene_; }
    const RenderOptions& options() const { return options_; }

    // Poses parts, rotates and blends the environment, moves the local lights
    // and the camera to time t, and recomputes the occluder lists.
    void set_time(float t);
    // The same with the camera at `camera` and the environment turned further
    // by `environment_rotation` (the viewer's orbit and environment drag).
    void set_view(float t, const Vec3& camera, const Mat3& environment_rotation);
    float time() const { return time_; }

    // The renderer's materials: swap a part's material (assign), edit a
    // parameter (set_parameter) or a whole material (replace). Only the
    // changed table is rebuilt, at the edit; the next shade() uses it.
    MaterialLibrary& materials() { return library_; }
    const MaterialLibrary& materials() const { return library_; }

    // The environment's RSL sets (one, or two to blend; frame_setup.h); the
    // current frame is recomputed at the same time.
    void set_environment_lights(EnvironmentLights lights);
    const EnvironmentLights& environment_lights() const { return environment_; }
    // The sphere lights (the scene's at construction); each needs radius > 0.
    void set_local_lights(std::vector<LocalLight> lights);
    const std::vector<LocalLight>& local_lights() const { return local_lights_; }

    // The frame at time(): poses, square lights, camera, occluder lists.
    const FrameSetup& frame() const { return frame_; }

    // Vertex colours of every part towards the camera; `out` must come from
    // make_output() (its buffers are reused).
    VertexColors make_output() const;
    virtual void shade(VertexColors& out) = 0;
    VertexColors shade() {
        VertexColors out = make_output();
        shade(out);
        return out;
    }
    // Counters of the last frame (what a backend does not count stays 0).
    const RenderStats& stats() const { return stats_; }

    // The image of the last shade() at `camera`: RGBA in linear radiance,
    // alpha the covered share of each pixel (premultiplied), S×S samples per
    // pixel (ImageFormationOptions). Every backend forms the same picture:
    // the vertex colours' blend, and the parts shaded per pixel
    // (RenderOptions::pixel_shadows, pixel_highlights) at each pixel's own
    // point (docs/design/RENDERER.md "Per-pixel shadows"). `colors` must be
    // that shade()'s output, made while keep_image_terms was on.
    Image form_image(const VertexColors& colors, const PinholeCamera& camera,
                     const ImageFormationOptions& options = {});
    // Whether shade() keeps what form_image needs for the parts shaded per
    // pixel (the CPU's per (vertex, light) terms: 3–8% of its shading time).
    // Off by default: callers that form images switch it on.
    void keep_image_terms(bool keep) { keep_image_terms_ = keep; }
    bool keeps_image_terms() const { return keep_image_terms_; }

    // The backend's own pass times of the last measured frame, as one line
    // for printing (`rsl render`); empty where it has none (the CPU).
    virtual std::string pass_times() const { return {}; }

    // By name, for command lines and demos; errors name the part, material
    // and parameter (and leave everything unchanged).
    void set_part_material(const std::string& part, const std::string& material);
    void set_material_parameter(const std::string& material, const std::string& key, const std::vector<float>& value);

protected:
    // `scene` must outlive the renderer. `environment_lights`: the
    // environment's RSL set (or the two sets of a blend) at rotation 0
    // (fit_environment_lights makes it). `fields` may lack any field (that
    // factor is then 1). The materials are the scene's with
    // options.material_override applied.
    VertexRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                   const RenderOptions& options);
    // The end of a backend's constructor: checks the scene's lights, sizes
    // the frame, and poses everything at t = 0 (the hooks below run).
    void start();

    // What a backend does beyond the shared state:
    // after a light set changed, before the frame is recomputed;
    virtual void lights_changed() {}
    // after every recomputed frame (stats_' occluder pairs already set);
    virtual void frame_changed() {}
    // the image of the last shade() (form_image checks the arguments).
    virtual Image backend_image(const VertexColors& colors, const PinholeCamera& camera,
                                const ImageFormationOptions& options) = 0;

    const Scene& scene_;
    RenderOptions options_;
    EnvironmentLights environment_;
    std::vector<LocalLight> local_lights_;
    PartFields fields_;
    MaterialLibrary library_;
    float time_ = 0;
    Mat3 view_rotation_{1.0f};
    std::optional<Vec3> view_camera_;
    FrameSetup frame_;  // after fields_: its culling reads the occluder fields
    RenderStats stats_;
    bool keep_image_terms_ = false;

private:
    void update_frame();
};

// Makes `out`'s layers follow the parts' current materials: a part whose
// material has a base colour texture gets a specular layer and the texture
// (VertexColors), others none. Allocates only where a part's layering
// changes; both renderers call it in shade(). Throws when a textured
// material (base colour or emission) is on a part without texture coordinates.
void match_layers(const MaterialLibrary& library, const Scene& scene, VertexColors& out);

// Adds each part's emission at its vertices (src/core/emission.h) to what a
// backend shaded: to a layered part's specular layer (the texture does not
// scale it), else to its colours; records it in `out.emission` for image
// formation. Both renderers call it last in shade(), so their vertex colours
// take emission from this one place.
void add_emission(const MaterialLibrary& library, const Scene& scene, VertexColors& out);

// A scene's material library with the options' per-part overrides applied
// (RenderOptions::material_override); errors name the scene file.
MaterialLibrary scene_material_library(const Scene& scene, const RenderOptions& options);

}  // namespace rsl
