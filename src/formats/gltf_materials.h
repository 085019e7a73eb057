#pragma once
// glTF 2.0 materials → scene materials (docs/SCENE_FORMAT.md, "glTF
// materials"): pbrMetallicRoughness becomes a gltf_pbr material, its
// baseColorTexture a Texture (decoded with Debian's stb_image, sRGB → linear),
// and the emission (emissiveFactor, emissiveTexture, emissive strength) its emissive.
// Internal to the glTF loader (gltf_loader.cpp), which includes tiny_gltf.h
// before this header.
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "src/core/scene.h"

namespace tinygltf {
class Model;
struct Image;
struct Material;
}  // namespace tinygltf

namespace rsl {

// Image index → why stb could not decode it (an error only if a material uses it).
using GltfImageErrors = std::map<int, std::string>;
// tinygltf's image loader callback (user data: GltfImageErrors*): 8-bit RGBA
// through stb_image; a failure is recorded, not fatal.
bool decode_gltf_image(tinygltf::Image* image, int image_index, std::string* error, std::string* warning,
                       int requested_width, int requested_height, const unsigned char* bytes, int size,
                       void* user_data);

class GltfMaterials {
public:
    GltfMaterials(const tinygltf::Model& model, const GltfImageErrors& image_errors,
                  const std::filesystem::path& path);

    // `material` if it is −1 or a valid glTF material index; throws otherwise.
    int checked_index(int material) const;
    // The TEXCOORD set a glTF material's textures read, −1 if it has none;
    // throws when two of its textures read different sets.
    int texcoord_set(int material) const;
    // The material's name ("material3" when unnamed; "default" for −1).
    std::string name(int material) const;
    // The scene material of a glTF material, added to `scene` at its first
    // use; −1 (no material) gives `default_material`.
    int scene_material(int material, Scene& scene, int default_material);
    // One warning per file for the material inputs rsl does not honour.
    void warn_ignored() const;

private:
    MaterialDesc convert(int material);
    enum class TextureEncoding { Srgb, Linear };
    void read_emission(const tinygltf::Material& source, const std::string& what, MaterialDesc& desc);
    // A decoded texture (`role` names it in errors: "base colour").
    std::shared_ptr<const Texture> texture(int texture_index, const std::string& what, const char* role,
                                           TextureEncoding encoding);

    const tinygltf::Model& model_;
    const GltfImageErrors& image_errors_;
    const std::filesystem::path& path_;
    std::map<int, int> scene_index_;                        // glTF material → scene material
    std::map<std::pair<int, TextureEncoding>, std::shared_ptr<const Texture>> textures_;  // glTF texture → decoded
    std::set<std::string> ignored_;                         // what warn_ignored reports
};

}  // namespace rsl
