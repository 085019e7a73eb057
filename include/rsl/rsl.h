#pragma once
// rsl's public C++ API: all-frequency environment lighting of dynamic scenes
// with rotatable square lights, for engines and scripts. Installed as
// <rsl/rsl.h>; in CMake, `find_package(rsl CONFIG REQUIRED)` and link
// `rsl::rsl` (docs/API.md, examples/embed/).
//
// It is a facade over what the `rsl` program runs — `rsl render` (scene,
// environment fit, fields from the cache, the renderer backends, image
// formation), `rsl truth`, `rsl fit`, `rsl compare` — not a pipeline of its
// own: a frame rendered here is the frame `rsl render` writes for the same
// scene, settings and time, bit for bit.
//
// Errors: bad input throws rsl::Error (<rsl/error.h>) whose what() is the
// message `rsl` prints after "rsl: error: " (it names the file and the
// problem); a bug in rsl throws rsl::InternalError.
//
// Threads: use one Renderer from one thread at a time; its long calls
// (construction, shade, render_image, truth) run on every core. Progress
// callbacks are called from worker threads, one call at a time.
//
// Conventions (docs/design/CONVENTIONS.md): right-handed world, y up; colours are
// linear RGB radiance; images have row 0 at the top.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rsl/error.h"
#include "rsl/version.h"

namespace rsl {
struct Scene;  // the library's own scene (src/core/scene.h); callers never see it
}

namespace rsl::api {

using Float3 = std::array<float, 3>;

// A rigid transform with scale: world = translation + rotation · (scale ⊙ local).
struct Pose {
    Float3 translation{0, 0, 0};
    std::array<float, 4> rotation{1, 0, 0, 0};  // quaternion (w, x, y, z), normalized when used
    Float3 scale{1, 1, 1};                      // positive
    // From a column-major 4×4 matrix (OpenGL/glm layout); throws rsl::Error
    // when it is not translation · rotation · scale (shear, mirror, projection).
    static Pose from_matrix(const std::array<float, 16>& column_major);
};

// A triangle mesh in the part's own frame.
struct Mesh {
    std::vector<Float3> positions;
    std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
    std::vector<Float3> normals;    // per vertex; empty: area-weighted normals are computed
};

// A BRDF by model name and parameters, as in a scene file's "materials"
// (docs/SCENE_FORMAT.md, docs/design/BRDF.md): e.g. {"floor", "lambert",
// {{"albedo", {0.5, 0.5, 0.5}}}}; `file` for measured (MERL) BRDFs. Any
// model takes "emissive" (RGB, or one value): radiance the surface gives off itself.
struct Material {
    std::string name;
    std::string model = "lambert";
    std::map<std::string, std::vector<float>> parameters;  // scalars as one value, RGB as three
    std::string file;
};

// A small spherical light: uniform emitter of radiant power `power` (W, RGB).
struct SphereLight {
    Float3 position{0, 0, 0};
    float radius = 0.05f;
    Float3 power{1, 1, 1};
};

// A rotatable square light ⟨c, r, I⟩ (docs/design/METHOD.md): radiance I over a
// square of solid angle 2r² around the unit direction c, at the environment's
// rotation 0.
struct SquareLight {
    Float3 center{0, 0, 1};
    float half_diagonal = 0;
    Float3 radiance{0, 0, 0};
};

struct Camera {
    Float3 position{0, 1, 4}, target{0, 0.5f, 0}, up{0, 1, 0};
    float fov_y_degrees = 40;
    int width = 640, height = 480;  // the default image size
};

// Field precomputation (docs/design/FIELDS.md); the defaults are the paper's
// but for the SVDF's 16 vectors (the paper's 8: a third more error on the bunny).
struct Precompute {
    int svdf_resolution = 32, svdf_clusters = 256, svdf_vectors = 16, svdf_supersampling = 4;
    int ovdf_shells = 16;
    // × the part's bounding radius; inner 0: chosen per mesh (0.4 where its
    // bounding sphere's centre lies inside it, else shells added inwards at
    // the same spacing down to 0.03: rooms, chairs, bowls).
    float ovdf_inner_radius = 0.0f, ovdf_outer_radius = 6.0f;
    int ovdf_cube_resolution = 32, ovdf_vdt_resolution = 32, ovdf_vectors = 8;
};

// A scene: rigid parts with materials, an environment map, sphere lights, a
// camera. Loaded from a file, or built in code. A value: copies are deep.
class Scene {
public:
    explicit Scene(const std::string& name = "scene");  // empty
    // A JSON scene file, a .gltf/.glb (one part per mesh node, its animation)
    // or one .obj (docs/SCENE_FORMAT.md); relative paths inside resolve
    // against the file's folder.
    static Scene load(const std::string& path);
    Scene(const Scene& other);
    Scene& operator=(const Scene& other);
    Scene(Scene&& other) noexcept;
    Scene& operator=(Scene&& other) noexcept;
    ~Scene();

    // Returns the material's index. Its parameters are checked when a
    // Renderer is made (the error names the material and parameter).
    int add_material(const Material& material);
    // Returns the part's index; `material` names an added material. The mesh
    // is checked as a file's would be (errors name the part).
    int add_part(const std::string& name, const Mesh& mesh, const std::string& material, const Pose& pose = {});
    // An environment map (.exr/.hdr, lat-long or cube strip) sampled on a cube
    // of 6 × resolution² texels, turning by degrees_per_second about `axis`.
    void set_environment(const std::string& file, int resolution = 32);
    void set_environment_rotation(const Float3& axis, float degrees, float degrees_per_second = 0);
    void add_sphere_light(const SphereLight& light);
    void set_camera(const Camera& camera);
    void set_precompute(const Precompute& settings);

    std::string name() const;
    std::vector<std::string> part_names() const;
    std::vector<std::string> material_names() const;
    std::vector<size_t> part_vertex_counts() const;
    size_t vertex_count() const;
    Camera camera() const;  // at time 0
    // A part's mesh as the renderer shades it, in the part's frame: vertex v
    // here is vertex v of the part's colours (loading and add_part drop
    // unused vertices and degenerate triangles, and split vertices where an
    // OBJ's normals differ).
    Mesh part_mesh(int part) const;
    Precompute precompute() const;
    std::string environment_file() const;
    int environment_resolution() const;
    // Every file the scene was read from (its file, meshes, maps, textures):
    // the files a write must not replace (write_image, write_vertex_colors).
    std::vector<std::string> input_files() const;

    // The library's scene, for rsl's own code (src/api).
    const rsl::Scene& internal() const { return *scene_; }

private:
    std::unique_ptr<rsl::Scene> scene_;
};

// Progress of long steps: (what, fraction of it done in [0, 1]). Called at
// most about ten times a second per step and always with 1 at its end.
using Progress = std::function<void(const std::string& what, double fraction)>;

struct RenderSettings {
    int lights = 30;                 // K: square lights fitted to the environment
    bool cross_face_lights = true;   // regions may cross cube-face borders (docs/design/LIGHTFIT.md)
    bool self_visibility = true;     // the SVDF factor
    bool occluders = true;           // the other parts' shadows (OVDF)
    // Which parts' images take the other parts' shadows per pixel where a
    // shadow edge crosses a triangle, as `rsl render --pixel-shadows`:
    // "planes" (flat rectangles: grounds, floors), "all" or "off". Every
    // backend's render_image(); form_image() draws the colours it is given.
    std::string pixel_shadows = "planes";
    // Glossy parts' images take the BRDF at each pixel's own normal and view
    // (highlights between vertices), as `rsl render --pixel-highlights`.
    bool pixel_highlights = true;
    // Each material's diffuse term takes the environment's exact irradiance,
    // the squares giving only its shadows (Heitz et al. 2018), as `rsl render
    // --exact-diffuse-light`; false: the RSL paper's sum (docs/design/RENDERER.md).
    bool exact_diffuse_light = true;
    // "cpu"; "rays": the CPU sum with every light's visibility from shadow
    // rays traced by Embree (the ray-traced baseline: no fields, so
    // self_visibility and occluders change nothing), see ray_samples; "gl":
    // the GPU renderer in an offscreen context of its own; "gl-current": the
    // GPU renderer in the OpenGL ≥ 4.3 core context current on the calling
    // thread (the engine's), see gl_color_buffer(); that context must be
    // current whenever the Renderer is used or destroyed. build_info()
    // lists the backends this library has.
    std::string backend = "cpu";
    // S: S×S jittered shadow rays per vertex and light (1 to 16), as `rsl
    // render --ray-samples`; another value than 1 needs a backend that
    // traces them ("rays").
    int ray_samples = 1;
    // Folder of the field files (made if missing; reused across runs and with
    // `rsl bake -o`). Empty: <scene folder>/.rsl-cache for a loaded scene; a
    // scene built in code then bakes in memory every time.
    std::string field_cache;
    std::map<std::string, std::string> part_materials;  // part → material, as `rsl render --material`
    Progress progress;                                  // fit and field bakes
};

// Per-vertex RGB of every part, parts in scene order, vertices in mesh order.
struct VertexColors {
    std::vector<std::string> part_names;
    std::vector<size_t> part_offsets;  // part p: vertices part_offsets[p] .. part_offsets[p + 1]
    std::vector<float> rgb;            // 3 per vertex
    float time = 0;
    std::string scene_name, producer;  // producer: "rsl-" and the backend ("rsl-cpu"), or "truth"
    size_t vertex_count() const { return rgb.size() / 3; }
};

// RGBA float image, row 0 at the top; colour premultiplied by alpha =
// the pixel's coverage by the scene (the EXR convention).
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgba;
};

struct ImageSettings {
    int width = 0, height = 0;  // 0: the camera's
    int samples = 1;            // S: S×S primary rays per pixel
};

struct TruthSettings {
    int subdivision = 1;      // S×S shadow rays per environment texel
    bool local_lights = true;
    Progress progress;
};

// What construction did (`rsl render` prints the same).
struct SetupReport {
    size_t lights = 0;             // environment square lights (both maps of a blend)
    int fields_loaded = 0, fields_baked = 0;
    double fit_seconds = 0, bake_seconds = 0;
};

// A renderer of one scene (its own copy of it). Per frame: change what moves
// (set_time, set_part_pose, set_environment_rotation, set_camera, lights,
// materials) in any order, then shade() or render_image(). truth() renders
// the same frame with the Embree ground truth.
class Renderer {
public:
    // Fits the environment, loads or bakes the fields, makes the backend.
    Renderer(const Scene& scene, const RenderSettings& settings = {});
    Renderer(Renderer&& other) noexcept;
    Renderer& operator=(Renderer&& other) noexcept;
    ~Renderer();

    std::string backend() const;  // "cpu", "rays", "gl", "gl-current"
    std::string device() const;   // where it runs ("GPU: EGL surfaceless: OpenGL 4.5 …")
    SetupReport setup() const;
    std::vector<std::string> part_names() const;
    std::vector<std::string> input_files() const;  // its scene's (Scene::input_files)
    // The part's world transform at the current frame (column-major 4×4),
    // to draw Scene::part_mesh with.
    std::array<float, 16> part_transform(int part) const;

    // Poses the scene's animation (parts, environment, lights, camera) at t.
    void set_time(float t);
    float time() const;
    // Puts a part at `pose` in the world from now on (its animation, and
    // that of its parent nodes, no longer moves it). By index or name.
    void set_part_pose(int part, const Pose& pose);
    void set_part_pose(const std::string& part, const Pose& pose);
    // The environment turned by `degrees` about `axis` from now on (the
    // scene's rotation animation is replaced).
    void set_environment_rotation(const Float3& axis, float degrees);
    void set_camera(const Camera& camera);  // from now on (its path is dropped)
    void set_sphere_lights(const std::vector<SphereLight>& lights);
    std::vector<SphereLight> sphere_lights() const;  // at rest (their paths are not shown)
    // The environment's square lights (the first map's, at rotation 0), e.g.
    // from fit_environment with another K.
    void set_environment_lights(const std::vector<SquareLight>& lights);
    std::vector<SquareLight> environment_lights() const;
    // Materials: swap a part's material for another of the scene's, or edit
    // one parameter (the BRDF table is rebuilt at the next frame; "emissive",
    // the radiance the surface gives off itself, rebuilds none: docs/SCENE_FORMAT.md).
    // Errors name the part, material and parameter and change nothing.
    void set_part_material(const std::string& part, const std::string& material);
    void set_material_parameter(const std::string& material, const std::string& key, const std::vector<float>& value);

    // Per-vertex colours of the current frame (for the gl backends, read
    // back from the GPU). A part with a base colour texture is given at unit
    // texture (its diffuse and specular sums added).
    VertexColors shade();
    // The image of vertex colours, formed by primary rays as `rsl render`
    // does (the scene posed at the current frame). Colours carry no texture
    // layers: a textured part is formed at unit texture; and no per-pixel
    // shadows or highlights: every part is its colours' blend.
    Image form_image(const VertexColors& colors, const ImageSettings& settings = {}) const;
    // Shades and forms the image as `rsl render` does, textured parts with
    // their base colour texture per pixel, and the per-pixel shadows and
    // highlights of RenderSettings::pixel_shadows and pixel_highlights.
    Image render_image(const ImageSettings& settings = {});
    // The ground truth (`rsl truth`) of the current frame: every environment
    // texel and light with shadow rays.
    VertexColors truth(const TruthSettings& settings = {}) const;

    // Backend "gl-current" only (else rsl::Error), in the caller's context:
    // shade_gl() runs the shading pass into gl_color_buffer(), a buffer of
    // one RGBA32F colour per vertex, parts in scene order (vertex i at byte
    // 16·i), to bind as GL_ARRAY_BUFFER and draw with the caller's pipeline.
    void shade_gl();
    unsigned gl_color_buffer() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

// `rsl bake`: every part's fields into `field_cache` (empty: beside the
// scene's file), baking only what is missing, as a Renderer's construction
// would. Returns how many field files were reused and baked (lights 0).
SetupReport bake_fields(const Scene& scene, const std::string& field_cache = "", const Progress& progress = {});

// `rsl fit`: the environment's K square lights and how well they rebuild it.
struct EnvironmentFit {
    std::vector<SquareLight> lights;
    int resolution = 0;          // the cube map's N
    double relative_l2 = 0;      // of the map rebuilt from the lights
    Float3 map_energy{}, light_energy{};
};
EnvironmentFit fit_environment(const std::string& file, int lights, int resolution = 32, bool cross_face = true);

// `rsl compare`: the error of a result against a reference.
struct VertexError {
    double relative_l2 = 0;    // ‖A − B‖₂ / ‖B‖₂ over RGB of every vertex
    double max_error = 0;      // largest RGB distance
    double relative_max = 0;   // max_error / largest |B|
    size_t count = 0;
    std::vector<std::string> part_names;
    std::vector<double> part_relative_l2;
    // The objects: every part but the static receivers, together, and the
    // worst of them (`rsl compare`'s line): a large ground can make the
    // all-vertex error look right while the objects on it are far off.
    double objects_relative_l2 = 0;
    size_t object_parts = 0;  // 0: every part is a receiver (the two below then say nothing)
    std::string worst_part;
    double worst_relative_l2 = 0;
};
// Both must describe the same vertices (else rsl::Error). `receivers`: the
// parts left out of the objects' error (`rsl compare --receivers`; a name
// matches ignoring case and an exporter's copy number: "Plane.001").
VertexError compare(const VertexColors& result, const VertexColors& reference,
                    const std::vector<std::string>& receivers = {"ground", "floor", "plane"});
struct ImageError {
    double relative_l2 = 0, relative_h1 = 0, max_error = 0;
    size_t covered = 0, total = 0;  // the pixels the reference covers count
};
ImageError compare(const Image& result, const Image& reference);

// Files, as the program writes them: `.exr` (and a tone-mapped `.png` beside
// it; exposure in stops, 0: automatic as `rsl render`), `.rslv` vertex colours.
// `inputs` (a scene's input_files()): a path that is one of them (by any
// spelling or link) is refused with rsl::Error naming both, nothing written.
void write_image(const std::string& exr_path, const Image& image, float exposure = 0,
                 const std::vector<std::string>& inputs = {});
Image read_image(const std::string& exr_path);
void write_vertex_colors(const std::string& rslv_path, const VertexColors& colors,
                         const std::vector<std::string>& inputs = {});
VertexColors read_vertex_colors(const std::string& rslv_path);

// The memory limit that loading and rendering a scene check their estimate
// against before allocating (bytes; 0: none), shared with the program's
// --memory-limit: 80% of the machine's memory unless the environment variable
// RSL_MEMORY_LIMIT or set_memory_limit says otherwise (docs/SCENE_FORMAT.md,
// "Memory"). A scene over it is refused with rsl::Error.
uint64_t memory_limit();
void set_memory_limit(uint64_t bytes);
void set_memory_limit(const std::string& size);  // "8G", "512M", "none"

// What this library is (`rsl --version`).
struct BuildInfo {
    std::string version, commit, build_type, embree, openexr;
    std::vector<std::string> backends;
};
BuildInfo build_info();

}  // namespace rsl::api
