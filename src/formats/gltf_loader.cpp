// glTF 2.0 (.gltf and .glb) through tinygltf: the default scene's node
// hierarchy, one rigid part per mesh node (per material of its primitives),
// node animation, materials (gltf_materials.cpp), lights, camera and
// extensions (gltf_extras.cpp). Every index and byte range in the file is
// checked before it is read, so corrupt files give an rsl::Error naming the file.
//
// tinygltf's implementation lives in this translation unit (configured by
// gltf_model.h; gltf_materials.cpp decodes base colour images with Debian's
// stb_image).
#define TINYGLTF_IMPLEMENTATION
#include "src/formats/gltf_file.h"
#include "src/formats/gltf_model.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>

#include <glm/gtx/matrix_decompose.hpp>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"
#include "src/formats/gltf_accessor_reader.h"
#include "src/formats/gltf_materials.h"
#include "src/formats/gltf_skins.h"
#include "src/core/skin_segments.h"
#include "src/core/scene.h"

namespace rsl {

namespace {

using gltf::AccessorReader;

// What the file reader below saw: the files it read, and why a read failed
// (by the path tinygltf asked for). tinygltf keeps an image's failure as a
// warning only, so a material using the image knew no reason for it.
struct FilesRead {
    std::vector<std::filesystem::path> read;
    std::map<std::string, std::string> failures;
};

// tinygltf reads files (the glTF itself, external buffers) with an ifstream
// and takes tellg() for their size: a directory reports 2^63 − 1 bytes and
// the allocation fails (std::bad_alloc, which `rsl` reported as an internal
// error), and a FIFO blocks. This reader reads regular files only, bounded,
// and records each in `files_read` (a FilesRead).
bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* files_read) {
    FilesRead& files = *static_cast<FilesRead*>(files_read);
    try {
        const std::string bytes = read_bounded_file(path, kMaxGltfFileBytes, "a glTF file or buffer");
        files.read.push_back(path);
        out->assign(bytes.begin(), bytes.end());
    } catch (const Error& e) {
        files.failures[path] = e.what();
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
    if (out->empty() && err) *err += "File is empty : " + path + "\n";
    return !out->empty();
}

// tinygltf parses and converts JSON recursively: a file nested a few
// hundred thousand levels deep overflowed the stack (a segfault). Real glTF
// files nest about ten levels; their extras, a few more.
constexpr int kMaxGltfJsonDepth = 256;

void check_json_depth(const std::filesystem::path& path, std::string_view json) {
    int depth = 0;
    bool in_string = false, escaped = false;
    for (const char c : json) {
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxGltfJsonDepth)
                throw_file_error(path, "JSON nested deeper than {} levels: not a glTF file rsl reads", kMaxGltfJsonDepth);
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

// The JSON chunk of a .glb (header, then chunk length and type), or what
// there is of it; tinygltf checks the layout itself.
std::string_view glb_json_chunk(std::string_view bytes) {
    if (bytes.size() < 20) return {};
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, sizeof(length));
    return bytes.substr(20, length);
}

// tinygltf's own FileExists opens the file (fopen), which blocks forever on a
// FIFO; a stat never blocks, and read_regular_file then refuses what is not
// a regular file, naming it.
bool path_exists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

struct LoadedGltf {
    tinygltf::Model model;
    GltfImageErrors image_errors;  // images stb could not decode: an error only if a material uses one
    std::vector<std::filesystem::path> files_read;  // the file, its buffers and its images
};

LoadedGltf read_model(const std::filesystem::path& path) {
    const bool binary_content = read_file_prefix(path, 4) == "glTF";
    const std::string extension = path.extension().string();
    const bool binary_name = extension == ".glb" || extension == ".GLB";
    if (binary_content != binary_name)
        throw_file_error(path, "mislabeled: the content is {} glTF but the name says {}",
                         binary_content ? "binary" : "text (JSON)", binary_name ? "binary (.glb)" : "text (.gltf)");

    FilesRead files_read;
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&path_exists, &tinygltf::ExpandFilePath, &read_regular_file,
                           &tinygltf::WriteWholeFile, &files_read});
    tinygltf::Model model;
    GltfImageErrors image_errors;
    loader.SetImageLoader(&decode_gltf_image, &image_errors);
    const std::string bytes = read_bounded_file(path, kMaxGltfFileBytes, "a glTF file");
    if (bytes.size() > std::numeric_limits<unsigned int>::max())  // tinygltf takes the length as unsigned int
        throw_file_error(path, "{} bytes: tinygltf reads at most 4 GiB", bytes.size());
    check_json_depth(path, binary_name ? glb_json_chunk(bytes) : std::string_view(bytes));
    std::string error, warning;
    const std::string base_dir = path.parent_path().string();
    const bool ok =
        binary_name ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  static_cast<unsigned int>(bytes.size()), base_dir)
                    : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(),
                                                 static_cast<unsigned int>(bytes.size()), base_dir);
    if (!ok) {
        while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
        throw_file_error(path, "not a valid glTF 2.0 file: {}", error.empty() ? "unknown error" : echo_message(error));
    }
    // An external image the reader refused: the material using it gives the reader's reason.
    for (size_t i = 0; i < model.images.size(); ++i) {
        const std::string& uri = model.images[i].uri;
        if (!model.images[i].image.empty() || uri.empty() || uri.rfind("data:", 0) == 0) continue;
        for (const auto& [file, reason] : files_read.failures)
            if (file.size() >= uri.size() && file.compare(file.size() - uri.size(), uri.size(), uri) == 0)
                image_errors.emplace(int(i), reason);
    }
    return LoadedGltf{std::move(model), std::move(image_errors), std::move(files_read.read)};
}

Transform rest_transform(const tinygltf::Node& node, const std::filesystem::path& path) {
    Transform t;
    if (node.matrix.size() == 16) {
        Mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = float(node.matrix[4 * c + r]);  // column-major, as glTF
        Vec3 skew;
        Vec4 perspective;
        if (!glm::decompose(m, t.scale, t.rotation, t.translation, skew, perspective))
            throw_file_error(path, "node '{}': matrix is not a rigid transform with scale", node.name);
        return t;
    }
    if (node.translation.size() == 3) t.translation = Vec3(node.translation[0], node.translation[1], node.translation[2]);
    if (node.scale.size() == 3) t.scale = Vec3(node.scale[0], node.scale[1], node.scale[2]);
    if (node.rotation.size() == 4)  // glTF stores (x, y, z, w)
        t.rotation = glm::normalize(Quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                                         float(node.rotation[2])));
    return t;
}

// Triangle list of one primitive, expanding strips and fans.
std::vector<uint32_t> triangle_indices(int mode, std::vector<uint32_t> corners) {
    if (mode == TINYGLTF_MODE_TRIANGLES || mode == -1) {
        corners.resize(corners.size() / 3 * 3);
        return corners;
    }
    std::vector<uint32_t> out;
    for (size_t k = 2; k < corners.size(); ++k) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const bool odd = k % 2 == 1;  // keep the winding consistent
            out.insert(out.end(), {corners[k - 2 + odd], corners[k - 1 - odd], corners[k]});
        } else {  // fan
            out.insert(out.end(), {corners[0], corners[k - 1], corners[k]});
        }
    }
    return out;
}

bool is_triangle_mode(int mode) {
    return mode == -1 || mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// Converts a loaded, unchecked tinygltf model into scene nodes and parts.
class GltfImporter {
public:
    GltfImporter(const LoadedGltf& loaded, const std::filesystem::path& path)
        : model_(loaded.model), image_errors_(loaded.image_errors), path_(path), reader_(loaded.model, path) {}

    void import_into(Scene& scene, int default_material, GltfMaterialUse use) {
        // Before any mesh is read: a compressed mesh's accessors have no data.
        gltf::check_required_extensions(model_, path_);
        const std::vector<int> parents = checked_parents();
        nodes_ = default_scene_nodes(parents);
        import_nodes(scene, parents);
        GltfMaterials materials(model_, image_errors_, path_);
        std::vector<std::optional<std::vector<MaterialMesh>>> converted(model_.meshes.size());
        skinned_.assign(model_.meshes.size(), std::nullopt);
        skin_of_.assign(model_.skins.size(), -1);
        for (size_t n = 0; n < model_.nodes.size(); ++n) {
            const int mesh_index = model_.nodes[n].mesh;
            if (mesh_index < 0 || nodes_.scene_node[n] < 0) continue;
            if (size_t(mesh_index) >= model_.meshes.size())
                throw_file_error(path_, "node {}: mesh index {} is out of range ({} meshes)", n, mesh_index,
                                 model_.meshes.size());
            if (model_.nodes[n].skin >= 0) {
                import_skinned_node(n, materials, scene, default_material, use);
                continue;
            }
            if (!converted[mesh_index]) converted[mesh_index] = material_meshes(mesh_index, materials);
            for (const MaterialMesh& piece : *converted[mesh_index]) {
                if (piece.mesh.indices.empty()) continue;  // only points/lines: not a surface
                Part part;
                part.name = scene.nodes[nodes_.scene_node[n]].name;
                // A mesh of several materials is one part per material.
                if (converted[mesh_index]->size() > 1) part.name += "/" + materials.name(piece.material);
                part.mesh = piece.mesh;
                part.mesh.name = part.name;
                part.node = nodes_.scene_node[n];
                part.material = use == GltfMaterialUse::Convert
                                    ? materials.scene_material(piece.material, scene, default_material)
                                    : default_material;
                scene.parts.push_back(std::move(part));
            }
        }
        materials.warn_ignored();
        import_animations(scene);
        gltf::import_lights(model_, path_, nodes_, scene);
        gltf::import_camera(model_, path_, nodes_, scene);
        std::vector<bool> used(model_.meshes.size());
        for (size_t m = 0; m < used.size(); ++m) used[m] = bool(converted[m]) || bool(skinned_[m]);
        warn_bind_pose(used);
        // One line per file, counting each glTF mesh once however many nodes use it.
        size_t dropped = 0;
        for (const auto& pieces : converted)
            if (pieces)
                for (const MaterialMesh& piece : *pieces) dropped += piece.mesh.degenerate_dropped;
        for (const auto& pieces : skinned_)
            if (pieces)
                for (const MaterialMesh& piece : *pieces) dropped += piece.mesh.degenerate_dropped;
        if (dropped) warn_file(path_, "{} degenerate triangle{} dropped", dropped, dropped == 1 ? "" : "s");
        scene.gltf_files.push_back({path_, model_.extensionsUsed, model_.extensionsRequired});
    }

private:
    // A skinned mesh node: one part per segment (src/core/skin_segments.h)
    // and material, named "<node>/<joint>" ("<node>/<joint>/<material>"
    // when the mesh has several materials), placed by its joint's node. The
    // node's own transform is ignored, as glTF specifies for skinned meshes.
    void import_skinned_node(size_t n, GltfMaterials& materials, Scene& scene, int default_material,
                             GltfMaterialUse use) {
        const tinygltf::Node& node = model_.nodes[n];
        const int mesh_index = node.mesh;
        if (node.skin >= int(model_.skins.size()))
            throw_file_error(path_, "node {}: skin index {} is out of range ({} skins)", n, node.skin,
                             model_.skins.size());
        int& skin_index = skin_of_[size_t(node.skin)];
        if (skin_index < 0) skin_index = gltf::import_skin(model_, path_, reader_, nodes_, node.skin, scene);
        const Skin& skin = scene.skins[size_t(skin_index)];
        if (!skinned_[mesh_index]) skinned_[mesh_index] = material_meshes(mesh_index, materials, true);
        const std::string node_name = scene.nodes[nodes_.scene_node[n]].name;
        for (MaterialMesh& piece : *skinned_[mesh_index]) {
            if (piece.mesh.indices.empty()) continue;
            SkinnedMesh skinned{piece.mesh, piece.joints, piece.weights};
            normalize_skin_weights(skinned, skin.joints.size(), path_, fmt::format("mesh '{}'", piece.mesh.name));
            for (SkinSegment& segment : split_skinned_mesh(skinned, skin)) {
                Part part;
                part.name = node_name + "/" + scene.nodes[skin.joints[size_t(segment.joint)]].name;
                if (skinned_[mesh_index]->size() > 1) part.name += "/" + materials.name(piece.material);
                part.mesh = std::move(segment.mesh);
                part.mesh.name = part.name;
                part.node = skin.joints[size_t(segment.joint)];
                part.material = use == GltfMaterialUse::Convert
                                    ? materials.scene_material(piece.material, scene, default_material)
                                    : default_material;
                segment.skin.skin = skin_index;
                segment.skin.mesh = piece.mesh.name;
                part.skin = std::make_shared<const PartSkin>(std::move(segment.skin));
                scene.parts.push_back(std::move(part));
            }
        }
    }

    // Every node's parent (-1: a root), after checking child indices, that
    // no node has two parents and that there is no cycle (node_world_at
    // would loop), over all the file's nodes.
    std::vector<int> checked_parents() const {
        std::vector<int> parents(model_.nodes.size(), -1);
        for (size_t n = 0; n < model_.nodes.size(); ++n) {
            for (int child : model_.nodes[n].children) {
                if (child < 0 || size_t(child) >= model_.nodes.size())
                    throw_file_error(path_, "node {}: child index {} is out of range ({} nodes)", n, child,
                                     model_.nodes.size());
                if (parents[child] >= 0) throw_file_error(path_, "node {} has two parents", child);
                parents[child] = int(n);
            }
        }
        for (size_t n = 0; n < model_.nodes.size(); ++n) {
            size_t steps = 0;
            for (int p = parents[n]; p >= 0; p = parents[p])
                if (++steps > model_.nodes.size()) throw_file_error(path_, "node {} is its own ancestor", n);
        }
        return parents;
    }

    // The file's `scene`, else scene 0; its root nodes and their descendants,
    // depth first. A file without scenes keeps every node (all its roots).
    gltf::SceneNodes default_scene_nodes(const std::vector<int>& parents) const {
        std::vector<int> roots;
        if (model_.scenes.empty()) {
            for (size_t n = 0; n < model_.nodes.size(); ++n)
                if (parents[n] < 0) roots.push_back(int(n));
        } else {
            const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (size_t(s) >= model_.scenes.size())
                throw_file_error(path_, "scene {} (the file's `scene`) is out of range ({} scenes)", s,
                                 model_.scenes.size());
            roots = model_.scenes[s].nodes;
            for (int r : roots)
                if (r < 0 || size_t(r) >= model_.nodes.size())
                    throw_file_error(path_, "scene {}: node index {} is out of range ({} nodes)", s, r,
                                     model_.nodes.size());
        }
        gltf::SceneNodes nodes;
        std::vector<bool> seen(model_.nodes.size(), false);
        for (int root : roots) {
            std::vector<int> stack{root};
            while (!stack.empty()) {
                const int n = stack.back();
                stack.pop_back();
                if (seen[n]) continue;
                seen[n] = true;
                nodes.order.push_back(n);
                const std::vector<int>& children = model_.nodes[n].children;
                stack.insert(stack.end(), children.rbegin(), children.rend());  // first child first
            }
        }
        // Scene nodes in the file's order, so that parts keep the file's order.
        nodes.scene_node.assign(model_.nodes.size(), -1);
        int next = 0;
        for (size_t n = 0; n < model_.nodes.size(); ++n)
            if (seen[n]) nodes.scene_node[n] = next++;
        return nodes;
    }

    void import_nodes(Scene& scene, const std::vector<int>& parents) {
        const int offset = int(scene.nodes.size());
        for (int& index : nodes_.scene_node)
            if (index >= 0) index += offset;
        for (size_t n = 0; n < model_.nodes.size(); ++n) {
            if (nodes_.scene_node[n] < 0) continue;
            const tinygltf::Node& source = model_.nodes[n];
            SceneNode node;
            node.name = source.name.empty() ? fmt::format("node{}", n) : source.name;
            node.rest = rest_transform(source, path_);
            // A listed root that has a parent outside the scene becomes a root.
            node.parent = parents[n] >= 0 ? nodes_.scene_node[parents[n]] : -1;
            scene.nodes.push_back(std::move(node));
        }
    }

    // Morph targets are not applied: their meshes render in their base
    // shape (docs/SCENE_FORMAT.md). One warning per file names them.
    void warn_bind_pose(const std::vector<bool>& used_meshes) const {
        std::vector<std::string> named;
        for (int n : nodes_.order) {
            const tinygltf::Node& node = model_.nodes[n];
            const int m = node.mesh;
            if (m < 0 || !used_meshes[m]) continue;
            const bool morphs = std::any_of(model_.meshes[m].primitives.begin(), model_.meshes[m].primitives.end(),
                                            [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
            if (!morphs) continue;
            const std::string what = node.skin >= 0 ? "skinned, with morph targets" : "morph targets";
            const std::string mesh = model_.meshes[m].name.empty() ? fmt::format("mesh{}", m) : model_.meshes[m].name;
            const std::string entry = fmt::format("mesh '{}' of node '{}' ({})", mesh,
                                                  node.name.empty() ? fmt::format("node{}", n) : node.name, what);
            if (std::find(named.begin(), named.end(), entry) == named.end()) named.push_back(entry);
        }
        if (named.empty()) return;
        warn_file(path_, "{} render{} without {} morph targets (their base shape): rsl does not apply morph targets",
                  fmt::join(named, ", "), named.size() == 1 ? "s" : "", named.size() == 1 ? "its" : "their");
    }

    struct MaterialMesh {
        int material = -1;  // glTF material index, −1 for none
        TriangleMesh mesh;
        std::vector<JointIndices> joints;  // with_skin: JOINTS_0 (and JOINTS_1) per vertex
        std::vector<JointWeights> weights; // with_skin: WEIGHTS_0 (and WEIGHTS_1) per vertex
    };
    // A glTF mesh's triangle primitives merged into one validated mesh per
    // material, in the order the materials first appear.
    std::vector<MaterialMesh> material_meshes(int mesh_index, const GltfMaterials& materials, bool with_skin = false) {
        std::vector<MaterialMesh> pieces;
        std::vector<std::vector<size_t>> primitives;
        const tinygltf::Mesh& source = model_.meshes[mesh_index];
        for (size_t p = 0; p < source.primitives.size(); ++p) {
            const int material = materials.checked_index(source.primitives[p].material);
            size_t k = 0;
            while (k < pieces.size() && pieces[k].material != material) ++k;
            if (k == pieces.size()) pieces.push_back({material, {}, {}, {}}), primitives.emplace_back();
            primitives[k].push_back(p);
        }
        for (size_t k = 0; k < pieces.size(); ++k)
            pieces[k].mesh = merged_mesh(mesh_index, primitives[k], materials.texcoord_set(pieces[k].material),
                                         with_skin ? &pieces[k] : nullptr);
        return pieces;
    }

    // The given triangle primitives of a glTF mesh merged into one validated
    // mesh, with texture coordinates TEXCOORD_<texcoord_set> when it is ≥ 0.
    // With `skin`, its joints and weights get JOINTS_0 and WEIGHTS_0 (required)
    // and JOINTS_1 and WEIGHTS_1 (optional, together).
    TriangleMesh merged_mesh(int mesh_index, const std::vector<size_t>& primitives, int texcoord_set,
                             MaterialMesh* skin = nullptr) {
        const tinygltf::Mesh& source = model_.meshes[mesh_index];
        TriangleMesh mesh;
        mesh.name = source.name.empty() ? fmt::format("mesh{}", mesh_index) : source.name;
        bool any_normals = false, any_tangents = false;
        for (size_t p : primitives) {
            const tinygltf::Primitive& primitive = source.primitives[p];
            if (!is_triangle_mode(primitive.mode)) continue;
            const std::string what = fmt::format("mesh '{}' primitive {}", mesh.name, p);
            const auto attribute = [&](const char* name) {
                auto it = primitive.attributes.find(name);
                return it == primitive.attributes.end() ? -1 : it->second;
            };
            const int position_accessor = attribute("POSITION");
            if (position_accessor < 0) throw_file_error(path_, "{} has no POSITION attribute", what);
            const std::vector<float> positions = reader_.floats(position_accessor, TINYGLTF_TYPE_VEC3, what + " POSITION");
            const size_t count = positions.size() / 3;
            const size_t base = mesh.positions.size();
            for (size_t v = 0; v < count; ++v) mesh.positions.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);

            // Zero normals/tangents mark missing ones: validation computes them.
            mesh.normals.resize(base + count, Vec3(0));
            if (const int a = attribute("NORMAL"); a >= 0) {
                const std::vector<float> normals = reader_.floats(a, TINYGLTF_TYPE_VEC3, what + " NORMAL");
                if (normals.size() != positions.size())
                    throw_file_error(path_, "{}: {} normals for {} positions", what, normals.size() / 3, count);
                for (size_t v = 0; v < count; ++v) mesh.normals[base + v] = Vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
                any_normals = true;
            }
            mesh.tangents.resize(base + count, Vec4(0));
            if (const int a = attribute("TANGENT"); a >= 0) {
                const std::vector<float> tangents = reader_.floats(a, TINYGLTF_TYPE_VEC4, what + " TANGENT");
                if (tangents.size() / 4 != count)
                    throw_file_error(path_, "{}: {} tangents for {} positions", what, tangents.size() / 4, count);
                for (size_t v = 0; v < count; ++v)
                    mesh.tangents[base + v] = Vec4(tangents[4 * v], tangents[4 * v + 1], tangents[4 * v + 2], tangents[4 * v + 3]);
                any_tangents = true;
            }
            if (texcoord_set >= 0) {
                const std::string name = fmt::format("TEXCOORD_{}", texcoord_set);
                const int a = attribute(name.c_str());
                if (a < 0)
                    throw_file_error(path_, "{}: its material has a texture but the primitive has no {}",
                                     what, name);
                const std::vector<float> uv = reader_.floats(a, TINYGLTF_TYPE_VEC2, what + " " + name);
                if (uv.size() / 2 != count)
                    throw_file_error(path_, "{}: {} texture coordinates for {} positions", what, uv.size() / 2, count);
                for (size_t v = 0; v < count; ++v) mesh.texcoords.emplace_back(uv[2 * v], uv[2 * v + 1]);
            }

            if (skin) read_skin_attributes(primitive, count, what, *skin);

            std::vector<uint32_t> corners;
            if (primitive.indices >= 0) {
                corners = reader_.indices(primitive.indices, what + " indices");
                for (size_t i = 0; i < corners.size(); ++i)
                    if (corners[i] >= count)
                        throw_file_error(path_, "{}: index {} is {}, out of range for {} vertices", what, i, corners[i], count);
            } else {
                corners.resize(count);
                for (size_t v = 0; v < count; ++v) corners[v] = uint32_t(v);
            }
            for (uint32_t& i : corners) i += uint32_t(base);
            const std::vector<uint32_t> triangles = triangle_indices(primitive.mode, std::move(corners));
            mesh.indices.insert(mesh.indices.end(), triangles.begin(), triangles.end());
        }
        if (!any_normals) mesh.normals.clear();
        if (!any_tangents) mesh.tangents.clear();
        if (mesh.indices.empty()) return mesh;
        std::vector<uint32_t> kept;
        validate_and_complete(mesh, path_, &kept);
        if (skin) {  // the attributes of the vertices validation kept
            for (size_t v = 0; v < kept.size(); ++v) {
                skin->joints[v] = skin->joints[kept[v]];
                skin->weights[v] = skin->weights[kept[v]];
            }
            skin->joints.resize(kept.size());
            skin->weights.resize(kept.size());
        }
        return mesh;
    }

    // Up to eight influences a vertex: sets 0 and 1 of JOINTS_n/WEIGHTS_n
    // (glTF 2.0 §3.7.3.3); a set 2 would be dropped, so it is refused.
    void read_skin_attributes(const tinygltf::Primitive& primitive, size_t count, const std::string& what,
                              MaterialMesh& skin) const {
        auto attribute = [&](const std::string& name) {
            const auto it = primitive.attributes.find(name);
            return it == primitive.attributes.end() ? -1 : it->second;
        };
        if (attribute("JOINTS_2") >= 0 || attribute("WEIGHTS_2") >= 0)
            throw_file_error(path_,
                             "{}: JOINTS_2/WEIGHTS_2: a vertex blends more than eight joints, and rsl blends at most "
                             "eight (JOINTS_0 and JOINTS_1)",
                             what);
        const size_t first = skin.joints.size();
        skin.joints.resize(first + count, JointIndices{});
        skin.weights.resize(first + count, JointWeights{});
        for (int set = 0; set < kJointsPerVertex / 4; ++set) {
            const std::string joints_name = fmt::format("JOINTS_{}", set);
            const std::string weights_name = fmt::format("WEIGHTS_{}", set);
            const int joints_accessor = attribute(joints_name), weights_accessor = attribute(weights_name);
            if (set > 0 && joints_accessor < 0 && weights_accessor < 0) break;
            if (joints_accessor < 0 || weights_accessor < 0) {
                const std::string& missing = joints_accessor < 0 ? joints_name : weights_name;
                if (set == 0) throw_file_error(path_, "{}: its node has a skin but the primitive has no {}", what, missing);
                throw_file_error(path_, "{}: it has {} but the primitive has no {}", what,
                                 joints_accessor < 0 ? weights_name : joints_name, missing);
            }
            const std::vector<float> joints =
                reader_.floats(joints_accessor, TINYGLTF_TYPE_VEC4, what + " " + joints_name);
            const std::vector<float> weights =
                reader_.floats(weights_accessor, TINYGLTF_TYPE_VEC4, what + " " + weights_name);
            if (joints.size() != 4 * count || weights.size() != 4 * count)
                throw_file_error(path_, "{}: {} {} and {} {} values for {} positions", what, joints.size() / 4, joints_name,
                                 weights.size() / 4, weights_name, count);
            for (size_t v = 0; v < count; ++v)
                for (int k = 0; k < 4; ++k) {
                    const float value = joints[4 * v + size_t(k)];
                    if (!(value >= 0 && value <= 65535 && value == std::floor(value)))
                        throw_file_error(path_, "{}: {} of vertex {} is {}, not a joint index", what, joints_name, v,
                                         value);
                    skin.joints[first + v][size_t(4 * set + k)] = uint16_t(value);
                    skin.weights[first + v][size_t(4 * set + k)] = weights[4 * v + size_t(k)];
                }
        }
    }

    Interpolation interpolation(const std::string& name, const std::string& what) const {
        if (name.empty() || name == "LINEAR") return Interpolation::Linear;
        if (name == "STEP") return Interpolation::Step;
        if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
        throw_file_error(path_, "{}: unknown interpolation '{}'", what, name);
    }

    // Animations that key different nodes play together (an exporter writes
    // one per object); where two key the same node and path, the first keeps
    // it and the file gets one warning naming the others.
    using KeyedBy = std::map<std::pair<int, std::string>, size_t>;  // (glTF node, path) → the animation keying it
    void import_animations(Scene& scene) {
        KeyedBy keyed_by;
        std::vector<std::string> overridden;
        size_t earliest_kept = model_.animations.size();
        for (size_t a = 0; a < model_.animations.size(); ++a)
            if (!played_.empty() && !played_[a]) continue;
            else if (const std::optional<size_t> kept = import_animation(a, scene, keyed_by)) {
                overridden.push_back(animation_name(a));
                earliest_kept = std::min(earliest_kept, *kept);
            }
        if (!overridden.empty())
            warn_file(path_,
                      "animation{} {} key{} nodes an earlier animation keys ({} first); on each node rsl plays the "
                      "earliest and leaves the later out",
                      overridden.size() == 1 ? "" : "s", fmt::join(overridden, ", "), overridden.size() == 1 ? "s" : "",
                      animation_name(earliest_kept));
    }
public:
    // Only the animations named (a scene file's `gltf_animations`); none: all.
    void select_animations(const std::vector<std::string>& names) {
        played_.clear();
        if (names.empty()) return;
        played_.assign(model_.animations.size(), false);
        for (const std::string& name : names) {
            bool found = false;
            for (size_t a = 0; a < model_.animations.size(); ++a)
                if (model_.animations[a].name == name || fmt::format("#{}", a) == name) played_[a] = found = true;
            if (!found) {
                std::vector<std::string> known;
                for (size_t a = 0; a < model_.animations.size(); ++a) known.push_back(animation_name(a));
                throw_file_error(path_, "no animation '{}' (the file has {})", echo_value(name),
                                 known.empty() ? std::string("none") : fmt::format("{}", fmt::join(known, ", ")));
            }
        }
    }

private:
    std::vector<bool> played_;  // per animation: whether it plays (empty: all)
    std::string animation_name(size_t a) const {
        const std::string& name = model_.animations[a].name;
        return name.empty() ? fmt::format("#{}", a) : fmt::format("'{}'", name);
    }

    // Imports one animation's channels. When a channel is left out because an
    // earlier animation keys the same node and path, returns that animation.
    std::optional<size_t> import_animation(size_t animation_index, Scene& scene, KeyedBy& keyed_by) {
        std::optional<size_t> kept;
        const tinygltf::Animation& animation = model_.animations[animation_index];
        for (size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = animation.channels[c];
            const std::string what = fmt::format("animation {} channel {}", animation_index, c);
            if (channel.target_path == "weights") continue;  // morph targets: not rigid motion
            if (channel.target_node < 0 || size_t(channel.target_node) >= model_.nodes.size())
                throw_file_error(path_, "{}: target node {} is out of range ({} nodes)", what, channel.target_node,
                                 model_.nodes.size());
            if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
                throw_file_error(path_, "{}: sampler {} is out of range ({} samplers)", what, channel.sampler,
                                 animation.samplers.size());
            const tinygltf::AnimationSampler& sampler = animation.samplers[channel.sampler];
            if (nodes_.scene_node[channel.target_node] < 0) continue;  // not in the default scene
            const Interpolation mode = interpolation(sampler.interpolation, what);
            const std::vector<float> times = reader_.floats(sampler.input, TINYGLTF_TYPE_SCALAR, what + " input");
            for (size_t k = 0; k < times.size(); ++k) {
                if (!std::isfinite(times[k]) || (k > 0 && times[k] < times[k - 1]))
                    throw_file_error(path_, "{}: key time {} ({}) is not finite and increasing", what, k, times[k]);
            }
            const size_t expected = mode == Interpolation::CubicSpline ? 3 * times.size() : times.size();
            const auto [keyed, first_here] =
                keyed_by.emplace(std::pair(channel.target_node, channel.target_path), animation_index);
            if (!first_here && keyed->second != animation_index) {
                kept = std::min(kept.value_or(keyed->second), keyed->second);
                continue;
            }
            SceneNode& node = scene.nodes[nodes_.scene_node[channel.target_node]];
            const bool is_rotation = channel.target_path == "rotation";
            if (!is_rotation && channel.target_path != "translation" && channel.target_path != "scale")
                throw_file_error(path_, "{}: unknown target path '{}'", what, channel.target_path);
            const std::vector<float> values =
                reader_.floats(sampler.output, is_rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, what + " output");
            const size_t n = is_rotation ? 4 : 3;
            if (values.size() / n != expected)
                throw_file_error(path_, "{}: {} output values for {} key times ({} interpolation)", what,
                                 values.size() / n, times.size(), sampler.interpolation);
            for (float v : values)
                if (!std::isfinite(v)) throw_file_error(path_, "{}: output value is not finite", what);
            if (is_rotation) {
                QuatTrack track{mode, times, {}};
                for (size_t k = 0; k < expected; ++k)  // glTF (x, y, z, w) → glm (w, x, y, z)
                    track.values.emplace_back(values[4 * k + 3], values[4 * k], values[4 * k + 1], values[4 * k + 2]);
                node.rotation = std::move(track);
            } else {
                Vec3Track track{mode, times, {}};
                for (size_t k = 0; k < expected; ++k) track.values.emplace_back(values[3 * k], values[3 * k + 1], values[3 * k + 2]);
                (channel.target_path == "translation" ? node.translation : node.scale) = std::move(track);
            }
        }
        return kept;
    }

    const tinygltf::Model& model_;
    const GltfImageErrors& image_errors_;
    const std::filesystem::path& path_;
    AccessorReader reader_;
    gltf::SceneNodes nodes_;
    std::vector<std::optional<std::vector<MaterialMesh>>> skinned_;  // per glTF mesh, converted with its skin attributes
    std::vector<int> skin_of_;  // per glTF skin: its index in scene.skins, or −1
};

}  // namespace

void load_gltf_into(const std::filesystem::path& path, Scene& scene, int default_material, GltfMaterialUse use,
                    const std::vector<std::string>& animations) {
    const LoadedGltf loaded = read_model(path);
    GltfImporter importer(loaded, path);
    importer.select_animations(animations);
    importer.import_into(scene, default_material, use);
    scene.input_files.push_back(path);
    scene.input_files.insert(scene.input_files.end(), loaded.files_read.begin(), loaded.files_read.end());
}

}  // namespace rsl
