#include "tools/assets/model.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "src/formats/gltf_model.h"  // tinygltf, configured as the loader compiles it

#include <fmt/format.h>
#include <stb_image_write.h>  // compiled in src/core/image.cpp

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"

namespace rsl::assets {

int GeneratedModel::add_node(std::string name, int parent, Vec3 translation, TriangleMesh mesh) {
    RSL_CHECK_LT(parent, int(scene.nodes.size()));
    SceneNode node;
    node.name = std::move(name);
    node.parent = parent;
    node.rest.translation = translation;
    scene.nodes.push_back(node);
    const int index = int(scene.nodes.size()) - 1;
    if (!mesh.indices.empty()) {
        Part part;
        part.name = scene.nodes.back().name;
        part.mesh = std::move(mesh);
        part.mesh.name = part.name;
        part.node = index;
        scene.parts.push_back(std::move(part));
    }
    return index;
}

int GeneratedModel::node(std::string_view name) const {
    for (size_t i = 0; i < scene.nodes.size(); ++i)
        if (scene.nodes[i].name == name) return int(i);
    throw_error("generated model '{}' has no node '{}'", scene.name, name);
}

QuatTrack loop_rotation_track(const std::function<Quat(float)>& rotation, float period, int keys) {
    RSL_CHECK_GE(keys, 2);
    QuatTrack track;
    track.interpolation = Interpolation::Linear;
    for (int k = 0; k <= keys; ++k) {
        const float t = period * k / keys;
        Quat q = k == keys ? track.values.front() : glm::normalize(rotation(t));
        if (k > 0 && glm::dot(q, track.values.back()) < 0) q = -q;
        track.times.push_back(t);
        track.values.push_back(q);
    }
    return track;
}

Vec3Track loop_translation_track(const std::function<Vec3(float)>& translation, float period, int keys) {
    RSL_CHECK_GE(keys, 2);
    Vec3Track track;
    track.interpolation = Interpolation::Linear;
    for (int k = 0; k <= keys; ++k) {
        const float t = period * k / keys;
        track.times.push_back(t);
        track.values.push_back(k == keys ? track.values.front() : translation(t));
    }
    return track;
}

namespace {

// Accumulates one binary buffer with 4-byte aligned views and their accessors.
class GltfBuilder {
public:
    explicit GltfBuilder(tinygltf::Model& model) : model_(model) { model_.buffers.resize(1); }

    // An accessor of `count` elements of `type` over view `view`.
    static tinygltf::Accessor accessor(int view, int component_type, size_t count, int type) {
        tinygltf::Accessor a;
        a.bufferView = view;
        a.componentType = component_type;
        a.count = count;
        a.type = type;
        return a;
    }

    int add_floats(const float* data, size_t count, int type, int components, int target, bool with_bounds) {
        tinygltf::Accessor a = accessor(add_view(data, count * components * sizeof(float), target),
                                        TINYGLTF_COMPONENT_TYPE_FLOAT, count, type);
        if (with_bounds) {  // required for POSITION and animation inputs
            a.minValues.assign(components, 1e300);
            a.maxValues.assign(components, -1e300);
            for (size_t i = 0; i < count; ++i)
                for (int c = 0; c < components; ++c) {
                    a.minValues[c] = std::min(a.minValues[c], double(data[i * components + c]));
                    a.maxValues[c] = std::max(a.maxValues[c], double(data[i * components + c]));
                }
        }
        model_.accessors.push_back(a);
        return int(model_.accessors.size()) - 1;
    }

    int add_joints(const std::vector<std::array<uint16_t, 4>>& joints) {
        const int view = add_view(joints.data(), joints.size() * sizeof(joints[0]), TINYGLTF_TARGET_ARRAY_BUFFER);
        model_.accessors.push_back(accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, joints.size(), TINYGLTF_TYPE_VEC4));
        return int(model_.accessors.size()) - 1;
    }

    int add_indices(const std::vector<uint32_t>& indices) {
        const int view = add_view(indices.data(), indices.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        model_.accessors.push_back(accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices.size(), TINYGLTF_TYPE_SCALAR));
        return int(model_.accessors.size()) - 1;
    }

    // Bytes with no accessor (an embedded image), as a buffer view.
    int add_bytes(const std::vector<unsigned char>& bytes) { return add_view(bytes.data(), bytes.size(), 0); }

private:
    int add_view(const void* data, size_t bytes, int target) {
        std::vector<unsigned char>& buffer = model_.buffers[0].data;
        buffer.resize((buffer.size() + 3) / 4 * 4, 0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buffer.size();
        view.byteLength = bytes;
        view.target = target;  // 0 (no target) for animation data
        const auto* bytes_in = static_cast<const unsigned char*>(data);
        buffer.insert(buffer.end(), bytes_in, bytes_in + bytes);
        model_.bufferViews.push_back(view);
        return int(model_.bufferViews.size()) - 1;
    }

    tinygltf::Model& model_;
};

std::vector<double> as_doubles(const float* v, int n) { return std::vector<double>(v, v + n); }

// A linear-RGB texture as the PNG bytes a glTF image holds: sRGB-encoded
// (colour textures: base colour, emissive) or linear (data textures: metallic-roughness).
std::vector<unsigned char> png_bytes(const Texture& texture, bool srgb) {
    const Image& image = texture.image;
    std::vector<unsigned char> pixels(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = srgb ? linear_to_srgb8(image.pixels[i])
                         : static_cast<unsigned char>(std::lround(std::clamp(image.pixels[i], 0.0f, 1.0f) * 255.0f));
    std::vector<unsigned char> png;
    const auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(context);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, pixels.data(), image.width * 3))
        throw_error("texture '{}': PNG encoding failed", texture.name);
    return png;
}

int gl_wrap(TextureWrap wrap) {
    if (wrap == TextureWrap::ClampToEdge) return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    if (wrap == TextureWrap::MirroredRepeat) return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    return TINYGLTF_TEXTURE_WRAP_REPEAT;
}

// A texture as an embedded PNG with its sampler; returns its index.
int add_texture(GltfBuilder& builder, tinygltf::Model& model, const Texture& source, bool srgb) {
    tinygltf::Image image;
    image.name = source.name;
    image.mimeType = "image/png";
    image.bufferView = builder.add_bytes(png_bytes(source, srgb));
    model.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter =
        source.filter == TextureFilter::Nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = sampler.magFilter;
    sampler.wrapS = gl_wrap(source.wrap_s);
    sampler.wrapT = gl_wrap(source.wrap_t);
    model.samplers.push_back(sampler);
    tinygltf::Texture texture;
    texture.source = int(model.images.size()) - 1;
    texture.sampler = int(model.samplers.size()) - 1;
    model.textures.push_back(texture);
    return int(model.textures.size()) - 1;
}

// A gltf_pbr scene material as a glTF material (its texture as an embedded
// PNG, as Blender's .glb export writes it); −1 for other models.
int add_material(GltfBuilder& builder, tinygltf::Model& model, const MaterialDesc& desc) {
    if (desc.model != "gltf_pbr") return -1;
    tinygltf::Material m;
    m.name = desc.name;
    const auto param = [&](const char* key, float fallback) {
        auto it = desc.params.find(key);
        return it == desc.params.end() ? std::vector<float>{fallback} : it->second;
    };
    const std::vector<float> base = param("base_color", 1.0f);
    m.pbrMetallicRoughness.baseColorFactor = {base[0], base[base.size() == 3 ? 1 : 0], base[base.size() == 3 ? 2 : 0], 1.0};
    m.pbrMetallicRoughness.metallicFactor = param("metallic", 1.0f)[0];
    m.pbrMetallicRoughness.roughnessFactor = param("roughness", 1.0f)[0];
    if (desc.base_color_texture)
        m.pbrMetallicRoughness.baseColorTexture.index = add_texture(builder, model, *desc.base_color_texture, true);
    if (desc.metallic_roughness_texture)
        m.pbrMetallicRoughness.metallicRoughnessTexture.index =
            add_texture(builder, model, *desc.metallic_roughness_texture, false);
    // Emission past 1 as glTF writes it: a factor in [0, 1] times KHR_materials_emissive_strength.
    const float strength = std::max({1.0f, desc.emissive.r, desc.emissive.g, desc.emissive.b});
    m.emissiveFactor = {desc.emissive.r / strength, desc.emissive.g / strength, desc.emissive.b / strength};
    if (strength > 1.0f) {
        tinygltf::Value::Object extension;
        extension["emissiveStrength"] = tinygltf::Value(double(strength));
        m.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(extension);
        if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_materials_emissive_strength") ==
            model.extensionsUsed.end())
            model.extensionsUsed.push_back("KHR_materials_emissive_strength");
    }
    if (desc.emissive_texture) m.emissiveTexture.index = add_texture(builder, model, *desc.emissive_texture, true);
    model.materials.push_back(m);
    return int(model.materials.size()) - 1;
}

void add_mesh(GltfBuilder& builder, tinygltf::Model& model, const Part& part, int material) {
    const TriangleMesh& mesh = part.mesh;
    RSL_CHECK_EQ(mesh.normals.size(), mesh.vertex_count());
    RSL_CHECK_EQ(mesh.tangents.size(), mesh.vertex_count());
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = builder.add_floats(&mesh.positions[0].x, mesh.vertex_count(), TINYGLTF_TYPE_VEC3,
                                                          3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    primitive.attributes["NORMAL"] = builder.add_floats(&mesh.normals[0].x, mesh.vertex_count(), TINYGLTF_TYPE_VEC3, 3,
                                                        TINYGLTF_TARGET_ARRAY_BUFFER, false);
    primitive.attributes["TANGENT"] = builder.add_floats(&mesh.tangents[0].x, mesh.vertex_count(), TINYGLTF_TYPE_VEC4,
                                                         4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    if (!mesh.texcoords.empty())
        primitive.attributes["TEXCOORD_0"] = builder.add_floats(&mesh.texcoords[0].x, mesh.vertex_count(),
                                                                TINYGLTF_TYPE_VEC2, 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    primitive.indices = builder.add_indices(mesh.indices);
    primitive.material = material;
    tinygltf::Mesh m;
    m.name = part.name;
    m.primitives.push_back(primitive);
    model.meshes.push_back(m);
}

// A skinned mesh on a new root node, with its skin.
void add_skin(GltfBuilder& builder, tinygltf::Model& model, tinygltf::Scene& root, const GeneratedSkin& skin,
              int material) {
    const size_t n = skin.mesh.vertex_count();
    RSL_CHECK_EQ(skin.joints.size(), n);
    RSL_CHECK_EQ(skin.weights.size(), n);
    RSL_CHECK_EQ(skin.inverse_bind.size(), skin.joint_nodes.size());
    Part part;
    part.name = skin.name;
    part.mesh = skin.mesh;
    add_mesh(builder, model, part, material);
    tinygltf::Primitive& primitive = model.meshes.back().primitives.back();
    // Set 1 only when some vertex blends more than four joints.
    const auto uses_set_1 = [](const JointWeights& w) {
        return std::any_of(w.begin() + 4, w.end(), [](float x) { return x != 0; });
    };
    const bool two_sets = std::any_of(skin.weights.begin(), skin.weights.end(), uses_set_1);
    for (int set = 0; set < (two_sets ? 2 : 1); ++set) {
        std::vector<std::array<uint16_t, 4>> joints(n);
        std::vector<float> weights(4 * n);
        for (size_t v = 0; v < n; ++v)
            for (size_t k = 0; k < 4; ++k) {
                joints[v][k] = skin.joints[v][size_t(4 * set) + k];
                weights[4 * v + k] = skin.weights[v][size_t(4 * set) + k];
            }
        primitive.attributes[fmt::format("JOINTS_{}", set)] = builder.add_joints(joints);
        primitive.attributes[fmt::format("WEIGHTS_{}", set)] =
            builder.add_floats(weights.data(), n, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    }
    tinygltf::Skin s;
    s.name = skin.name;
    s.joints = skin.joint_nodes;
    std::vector<float> matrices;
    for (const Mat4& m : skin.inverse_bind)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) matrices.push_back(m[c][r]);
    s.inverseBindMatrices =
        builder.add_floats(matrices.data(), skin.inverse_bind.size(), TINYGLTF_TYPE_MAT4, 16, 0, false);
    model.skins.push_back(s);
    tinygltf::Node node;
    node.name = skin.name;
    node.mesh = int(model.meshes.size()) - 1;
    node.skin = int(model.skins.size()) - 1;
    model.nodes.push_back(node);
    root.nodes.push_back(int(model.nodes.size()) - 1);
}

void add_channel(GltfBuilder& builder, tinygltf::Animation& animation, const std::vector<float>& times,
                 const float* values, int components, int node, const char* path) {
    RSL_CHECK_GE(times.size(), size_t(1));
    tinygltf::AnimationSampler sampler;
    sampler.input = builder.add_floats(times.data(), times.size(), TINYGLTF_TYPE_SCALAR, 1, 0, true);
    sampler.output = builder.add_floats(values, times.size(), components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                        components, 0, false);
    sampler.interpolation = "LINEAR";
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = int(animation.samplers.size()) - 1;
    channel.target_node = node;
    channel.target_path = path;
    animation.channels.push_back(channel);
}

}  // namespace

void write_glb(const std::filesystem::path& path, const GeneratedModel& generated) {
    const Scene& scene = generated.scene;
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "rsl assets (tools/assets)";
    GltfBuilder builder(model);

    model.nodes.resize(scene.nodes.size());
    tinygltf::Scene root;
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        const SceneNode& source = scene.nodes[n];
        tinygltf::Node& node = model.nodes[n];
        node.name = source.name;
        node.translation = as_doubles(&source.rest.translation.x, 3);
        const Quat& q = source.rest.rotation;  // glTF order (x, y, z, w)
        node.rotation = {q.x, q.y, q.z, q.w};
        if (source.rest.scale != Vec3(1)) node.scale = as_doubles(&source.rest.scale.x, 3);
        if (source.parent >= 0) model.nodes[source.parent].children.push_back(int(n));
        else root.nodes.push_back(int(n));
    }
    // Parts with identical meshes (instances) share one glTF mesh, as an
    // exporter writes a mesh used by several nodes.
    std::vector<const Part*> written;
    std::vector<int> materials(scene.materials.size(), -2);  // scene material → glTF material (−2: not yet)
    for (const Part& part : scene.parts) {
        RSL_CHECK(part.node >= 0 && part.node < int(scene.nodes.size()));
        const auto same = std::find_if(written.begin(), written.end(), [&](const Part* other) {
            return other->mesh.indices == part.mesh.indices && other->mesh.positions == part.mesh.positions &&
                   other->mesh.normals == part.mesh.normals && other->mesh.tangents == part.mesh.tangents &&
                   other->mesh.texcoords == part.mesh.texcoords && other->material == part.material;
        });
        if (same != written.end()) {
            model.nodes[part.node].mesh = int(same - written.begin());
            continue;
        }
        model.nodes[part.node].mesh = int(model.meshes.size());
        int material = -1;
        if (part.material >= 0 && size_t(part.material) < scene.materials.size()) {
            int& m = materials[size_t(part.material)];
            if (m == -2) m = add_material(builder, model, scene.materials[size_t(part.material)]);
            material = m;
        }
        add_mesh(builder, model, part, material);
        written.push_back(&part);
    }
    for (const GeneratedSkin& skin : generated.skins) {
        int material = -1;
        if (skin.material >= 0 && size_t(skin.material) < scene.materials.size()) {
            int& m = materials[size_t(skin.material)];
            if (m == -2) m = add_material(builder, model, scene.materials[size_t(skin.material)]);
            material = m;
        }
        add_skin(builder, model, root, skin, material);
    }
    model.scenes.push_back(root);
    model.defaultScene = 0;

    tinygltf::Animation animation;
    animation.name = generated.animation_name;
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        const SceneNode& node = scene.nodes[n];
        RSL_CHECK(!node.scale);  // rigid motion only
        if (node.rotation) {
            std::vector<float> xyzw;
            for (const Quat& q : node.rotation->values) xyzw.insert(xyzw.end(), {q.x, q.y, q.z, q.w});
            add_channel(builder, animation, node.rotation->times, xyzw.data(), 4, int(n), "rotation");
        }
        if (node.translation)
            add_channel(builder, animation, node.translation->times, &node.translation->values[0].x, 3, int(n),
                        "translation");
    }
    if (!animation.channels.empty()) model.animations.push_back(animation);

    std::ostringstream stream;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, stream, false, true))
        throw_file_error(path, "tinygltf could not serialize the model");
    write_file_atomically(path, stream.str());
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh) {
    RSL_CHECK_EQ(mesh.normals.size(), mesh.vertex_count());
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "# {} — generated by rsl assets (tools/assets)\n", mesh.name);
    fmt::format_to(std::back_inserter(out), "# {} vertices, {} triangles\n", mesh.vertex_count(), mesh.triangle_count());
    for (const Vec3& p : mesh.positions) fmt::format_to(std::back_inserter(out), "v {:.6g} {:.6g} {:.6g}\n", p.x, p.y, p.z);
    for (const Vec3& n : mesh.normals) fmt::format_to(std::back_inserter(out), "vn {:.6g} {:.6g} {:.6g}\n", n.x, n.y, n.z);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t a = mesh.indices[3 * t] + 1, b = mesh.indices[3 * t + 1] + 1, c = mesh.indices[3 * t + 2] + 1;
        fmt::format_to(std::back_inserter(out), "f {0}//{0} {1}//{1} {2}//{2}\n", a, b, c);
    }
    write_file_atomically(path, std::string_view(out.data(), out.size()));
}

}  // namespace rsl::assets
