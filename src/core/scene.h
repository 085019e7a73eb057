#pragma once
// A dynamic scene: rigid parts (from glTF nodes or OBJ files) with animation,
// an environment map with its rotation, materials, local lights, a camera.
// Loaded from a JSON scene file (schema in docs/SCENE_FORMAT.md) or from a single mesh.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "src/core/math.h"
#include "src/core/mesh.h"
#include "src/core/subdivide.h"
#include "src/core/texture.h"
#include "src/shading/squares.h"

namespace rsl {

// glTF-style keyframe track (times in seconds).
enum class Interpolation { Step, Linear, CubicSpline };
struct Vec3Track {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;
    std::vector<Vec3> values;
    Vec3 sample(float t) const;  // clamps outside [times.front(), times.back()]
};
struct QuatTrack {
    Interpolation interpolation = Interpolation::Linear;  // Linear = slerp
    std::vector<float> times;
    std::vector<Quat> values;
    Quat sample(float t) const;
};

struct Transform {
    Vec3 translation{0};
    Quat rotation{1, 0, 0, 0};
    Vec3 scale{1};
    Mat4 matrix() const;
};

struct SceneNode {
    std::string name;
    int parent = -1;
    Transform rest;  // local transform when not animated
    std::optional<Vec3Track> translation;
    std::optional<QuatTrack> rotation;
    std::optional<Vec3Track> scale;
    Transform local_at(float t) const;
};

// A material: BRDF model name and its parameters, as the scene file gives them
// (validated by the BRDF module, which owns the meaning of each parameter).
struct MaterialDesc {
    std::string name;
    std::string model = "lambert";
    std::map<std::string, std::vector<float>> params;  // scalars are 1-vectors, RGB are 3-vectors
    std::filesystem::path file;  // measured BRDFs (MERL .binary)
    // glTF baseColorTexture (gltf_pbr only): multiplies the diffuse lobe per
    // pixel, read at the part's TEXCOORD_0 (docs/SCENE_FORMAT.md).
    std::shared_ptr<const Texture> base_color_texture;
    // glTF metallicRoughnessTexture (gltf_pbr only; linear, G = roughness,
    // B = metallic, times the factors): both vary per vertex, read at the
    // same texture coordinates (docs/design/BRDF.md "Textured roughness and metallic").
    std::shared_ptr<const Texture> metallic_roughness_texture;
    // Emission (src/core/emission.h): radiance the surface gives off itself,
    // emissive × emissive_texture(uv), added to what it reflects; it lights
    // no other surface. glTF: emissiveFactor × KHR_materials_emissive_strength.
    Color emissive{0};
    std::shared_ptr<const Texture> emissive_texture;  // sRGB-decoded, read at the part's texture coordinates
};

// A glTF skin: its joints' scene nodes and inverse bind matrices (mesh
// bind space → joint frame), src/core/skinning.h.
struct Skin {
    std::string name;
    std::vector<int> joints;
    std::vector<Mat4> inverse_bind;
};

// A vertex blends up to eight joints: glTF's JOINTS_0/WEIGHTS_0 and, when
// present, JOINTS_1/WEIGHTS_1. Unused slots have weight 0.
inline constexpr int kJointsPerVertex = 8;
using JointIndices = std::array<uint16_t, kJointsPerVertex>;
using JointWeights = std::array<float, kJointsPerVertex>;

// A segment of a skinned mesh (docs/design/SKINNING.md): the part's mesh is
// its bind-pose geometry in its joint's frame, and each vertex blends up to
// eight of the skin's joints (linear blend skinning, src/core/skinning.h).
struct PartSkin {
    int skin = -1;   // index into Scene::skins
    int joint = -1;  // the segment's joint (index into the skin's joints); the part's node is its node
    std::string mesh;  // the skinned glTF mesh's name (`rsl info`)
    std::vector<JointIndices> joints;  // per vertex: indices into the skin's joints
    std::vector<JointWeights> weights; // per vertex: sum 1, by decreasing weight
};

struct Part {
    std::string name;
    TriangleMesh mesh;  // in the part's frame
    int node = -1;      // scene node giving its transform
    int material = 0;   // index into Scene::materials
    size_t loaded_vertices = 0;  // as the file gave them, before subdivide_scene_parts (`rsl info`)
    std::shared_ptr<const PartSkin> skin;  // a skinned mesh's segment, or null (a rigid part)
};

struct Scene;

// A glTF point or spot light's radius unless the scene file's `light_radii`
// gives one (scene units; 5 cm in glTF's metres: a light bulb).
inline constexpr float kGltfLightRadius = 0.05f;

// A small spherical light. Scene-file lights have a position (or a keyed
// path); a glTF light (KHR_lights_punctual) hangs on a scene node and moves
// with it. A spot light's cone scales what reaches a point in direction w
// (light → point, unit) by shading::spot_cone_factor (glTF's smooth falloff,
// docs/SCENE_FORMAT.md "glTF lights"); a point light has no cone.
struct LocalLight {
    std::string name;  // the glTF light's node (for `light_radii`); empty for scene-file lights
    float radius = 0.05f;
    Color power{1};  // RGB radiant power (W); radiance of the sphere = power / (4π² a²)
    Vec3 position{0};  // without a node; with one, its world position at the scene's start (for display)
    std::optional<Vec3Track> path;
    int node = -1;  // the scene node whose origin it sits at (−Z is the spot axis), or -1
    bool spot = false;
    float inner_cone_radians = 0, outer_cone_radians = 0;  // spot: 0 ≤ inner < outer ≤ π/2
    Vec3 axis{0, 0, -1};  // spot axis without a node (world space, unit)

    Vec3 position_at(const Scene& scene, float t) const;
    Vec3 axis_at(const Scene& scene, float t) const;  // unit
};

// A directional light (a glTF "sun", KHR_lights_punctual): irradiance E per
// channel at normal incidence, from the direction opposite its node's −Z.
// The renderers light with it as one square light of the sun's size after
// the environment map's (fit_scene_lights, src/render/cpu_renderer.h), the
// ground truth as a direction of irradiance E; it turns with the map.
struct SunLight {
    std::string name;  // its node's
    int node = -1;     // the scene node whose −Z it shines along
    Color irradiance{0};

    // Unit direction towards the sun (world) at time t.
    Vec3 direction_at(const Scene& scene, float t) const;
};

struct EnvironmentDesc {
    std::filesystem::path file;  // empty: no map (black), unless `uniform` or `suns` light it
    int resolution = 32;  // cube map N
    Vec3 rotation_axis{0, 1, 0};
    float rotation_degrees = 0;            // at t = 0
    float rotation_degrees_per_second = 0;
    std::filesystem::path second_file;     // optional: blend towards this map over time
    float blend_period_seconds = 0;
    Mat3 rotation_at(float t) const;
    // Weight w of the second map at time t (docs/SCENE_FORMAT.md): the
    // environment is (1 − w)·file + w·second_file, both turned by
    // rotation_at(t), with w = ½ − ½·cos(2π·t / blend_period_seconds): the
    // first map alone at t = 0, the second alone at half the period, back at
    // a full period. 0 without a second map.
    float blend_weight_at(float t) const;
    // A uniform sky added to the map (the bare mesh files' default, radiance 1).
    Color uniform{0};
    std::vector<SunLight> suns;  // glTF directional lights
    // Whether anything lights the scene from afar (a map, a uniform sky or a sun).
    bool present() const { return !file.empty() || uniform.r > 0 || uniform.g > 0 || uniform.b > 0 || !suns.empty(); }
};

struct Camera {
    Vec3 position{0, 1, 4}, target{0, 0.5f, 0}, up{0, 1, 0};
    float fov_y_degrees = 40;
    int width = 640, height = 480;
    std::optional<Vec3Track> position_path, target_path;
    Vec3 position_at(float t) const { return position_path ? position_path->sample(t) : position; }
    Vec3 target_at(float t) const { return target_path ? target_path->sample(t) : target; }
};

// A glTF file's camera (the first perspective camera node of its default
// scene): used when the scene file gives no camera pose (docs/SCENE_FORMAT.md).
struct GltfCamera {
    std::string name;  // the node's
    int node = -1;     // scene node: the camera looks along its −Z, +Y up
    float fov_y_degrees = 40;
    bool used = false;  // the scene's camera is this one (the scene file gives no pose)
};

// What a loaded glTF file uses that rsl reads or drops, for `rsl info`.
struct GltfFileNotes {
    std::filesystem::path file;
    std::vector<std::string> extensions_used, extensions_required;
};

struct AnimationRange {
    float start = 0, end = 0, fps = 24;
};

// Precomputation settings (src/fields/). Defaults follow the paper.
struct PrecomputeSettings {
    int svdf_resolution = 32;
    int svdf_clusters = 256;
    int svdf_vectors = 16;  // docs/design/FIELDS.md "SVDF": the bunny's error falls most per byte here
    int svdf_supersampling = 4;  // rays per texel side
    int ovdf_shells = 16;
    float ovdf_inner_radius = 0.0f;  // × bounding radius; 0: per mesh (src/fields/ovdf.h ovdf_params_for_mesh)
    float ovdf_outer_radius = 6.0f;
    int ovdf_cube_resolution = 32;
    int ovdf_vdt_resolution = 32;
    int ovdf_vectors = 8;
};

struct Scene {
    std::string name;
    std::filesystem::path source;  // the file it was loaded from
    // Every file read to build it: the scene file, meshes, glTF files with
    // their buffers and images, environment maps, measured BRDFs. No output
    // may overwrite one (check_outputs_apart, src/core/atomic_file.h).
    std::vector<std::filesystem::path> input_files;
    std::vector<SceneNode> nodes;
    std::vector<Part> parts;
    std::vector<Skin> skins;
    std::vector<MaterialDesc> materials;
    std::vector<LocalLight> lights;
    EnvironmentDesc environment;
    Camera camera;
    std::optional<GltfCamera> gltf_camera;  // the first glTF file's camera, if it has one
    std::vector<GltfFileNotes> gltf_files;
    AnimationRange animation;
    PrecomputeSettings precompute;
    SubdivisionSettings subdivision;

    Mat4 node_world_at(int node, float t) const;  // product of ancestors' local transforms
    Mat4 part_transform_at(int part, float t) const { return node_world_at(parts[part].node, t); }
    size_t vertex_count() const;
};

// Splits every part's long edges per scene.subdivision (src/core/subdivide.h)
// and records each part's loaded vertex count. load_scene
// (src/formats/scene_file.h) calls it; a scene built in code calls it when it
// wants the same meshes a file would give.
void subdivide_scene_parts(Scene& scene);

}  // namespace rsl
