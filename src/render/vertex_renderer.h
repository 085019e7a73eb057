#pragma once
// What every runtime renderer does, whatever runs the sum (the CPU renderer,
// src/render/renderer.h; the GL one, src/gl/gl_renderer.h): pose the scene at
// a time, swap and edit materials, change the lighting, and shade every
// vertex into VertexColors. `rsl render`, the demos and the benchmarks hold a
// VertexRenderer from make_renderer (src/backend/make_renderer.h), so a new
// backend implements this class and one case of that factory.
//
// Call order per frame: edits (materials, lights) at any time between
// frames, then set_time (or set_view), then shade. Material edits made
// through materials() take effect at the next shade(): the renderer compares
// each material's revision() with the one it last built from, and rebuilds
// (CPU) or re-uploads (GL) only the tables that changed.
#include <optional>
#include <string>
#include <vector>

#include "src/brdf/material_library.h"
#include "src/core/scene.h"
#include "src/render/frame_setup.h"
#include "src/render/render_options.h"
#include "src/frame/image_formation.h"
#include "src/frame/vertex_colors.h"

namespace rsl {

class VertexRenderer {
public:
    virtual ~VertexRenderer() = default;

    // "cpu", "gl": what `rsl render` prints and the .rslv producer says.
    virtual std::string backend() const = 0;
    // A line about where it runs ("GPU: EGL surfaceless: OpenGL 4.5 …"); the backend by default.
    virtual std::string device() const { return backend(); }
    // The scene it renders (it must outlive the renderer).
    virtual const Scene& scene() const = 0;

    // Poses parts, rotates and blends the environment, moves the local lights
    // and the camera to time t, and recomputes the occluder lists.
    virtual void set_time(float t) = 0;
    // The same with the camera at `camera` and the environment turned further
    // by `environment_rotation` (the viewer's orbit and environment drag).
    virtual void set_view(float t, const Vec3& camera, const Mat3& environment_rotation) = 0;
    virtual float time() const = 0;

    // The renderer's materials: swap a part's material (assign), edit a
    // parameter (set_parameter) or a whole material (replace). Only the
    // changed table is rebuilt, at the edit; the next shade() uses it.
    virtual MaterialLibrary& materials() = 0;
    virtual const MaterialLibrary& materials() const = 0;

    // The environment's RSL sets (one, or two to blend; frame_setup.h); the
    // current frame is recomputed at the same time.
    virtual void set_environment_lights(EnvironmentLights lights) = 0;
    virtual const EnvironmentLights& environment_lights() const = 0;
    // The sphere lights (the scene's at construction); each needs radius > 0.
    virtual void set_local_lights(std::vector<LocalLight> lights) = 0;
    virtual const std::vector<LocalLight>& local_lights() const = 0;

    // Vertex colours of every part towards the camera; `out` must come from
    // make_output() (its buffers are reused).
    virtual VertexColors make_output() const = 0;
    virtual void shade(VertexColors& out) = 0;
    VertexColors shade() {
        VertexColors out = make_output();
        shade(out);
        return out;
    }
    // Counters of the last frame (what a backend does not count stays 0).
    virtual const RenderStats& stats() const = 0;
    // The parts this renderer shades per pixel in an image of `colors`, its
    // last shade()'s output, for form_image (RenderOptions::pixel_shadows,
    // pixel_highlights; that shade() must have kept the terms, below); valid
    // until the next shade() or set_time(). Empty: every part is its vertex
    // colours' blend (the GL backend's today).
    // `posed`: the scene posed at the frame's time, whose hits the shaders colour.
    virtual PartShaders pixel_shading(const VertexColors& colors, const PosedScene& posed) const { return {}; }
    // Whether shade() keeps what pixel_shading needs (per (vertex, light)
    // terms of the parts shaded per pixel: 3–8% of the CPU's shading time).
    // Off by default: callers that form images with it switch it on.
    virtual void keep_pixel_terms(bool keep) {}
    // The image of the last shade() at `camera`, formed by the backend on its
    // device (the GL backend: the vertex colours rasterized and its per-pixel
    // pass, what the viewer shows; src/gl/gl_renderer.h form_image), RGBA in
    // linear radiance with one sample per pixel; nullopt where the backend
    // forms none (the CPU: form_image with pixel_shading).
    virtual std::optional<Image> device_image(const PinholeCamera& camera) { return std::nullopt; }
    // The backend's own pass times of the last measured frame, as one line
    // for printing (`rsl render`); empty where it has none (the CPU).
    virtual std::string pass_times() const { return {}; }

    // By name, for command lines and demos; errors name the part, material
    // and parameter (and leave everything unchanged).
    void set_part_material(const std::string& part, const std::string& material);
    void set_material_parameter(const std::string& material, const std::string& key, const std::vector<float>& value);

protected:
    // For implementations: the frame state they share (frame_setup.h) is
    // recomputed by the same code; these check the lights they are given.
    static void check_local_lights(const Scene& scene, const std::vector<LocalLight>& lights);
};

// Makes `out`'s layers follow the parts' current materials: a part whose
// material has a base colour texture gets a specular layer and the texture
// (VertexColors), others none. Allocates only where a part's layering
// changes; both renderers call it in shade(). Throws when a textured
// material is on a part without texture coordinates.
void match_layers(const MaterialLibrary& library, const Scene& scene, VertexColors& out);

// A scene's material library with the options' per-part overrides applied
// (RenderOptions::material_override); errors name the scene file.
MaterialLibrary scene_material_library(const Scene& scene, const RenderOptions& options);

}  // namespace rsl
