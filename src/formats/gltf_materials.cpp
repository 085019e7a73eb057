// glTF materials and base colour textures (gltf_materials.h).
#include "src/formats/gltf_model.h"  // tinygltf, configured as the loader compiles it

// The one translation unit that compiles stb_image (Debian's libstb-dev
// header; the tests' PNG reader uses it too), for the two formats glTF 2.0
// core allows.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#include <stb_image.h>
#pragma GCC diagnostic pop

#include "src/formats/gltf_materials.h"

#include <array>

#include <fmt/format.h>

#include "src/core/emission.h"
#include "src/core/error.h"
#include "src/core/scene_limits.h"
#include "src/formats/file_reading.h"

namespace rsl {

bool decode_gltf_image(tinygltf::Image* image, int image_index, std::string*, std::string*, int, int,
                       const unsigned char* bytes, int size, void* user_data) {
    auto* errors = static_cast<GltfImageErrors*>(user_data);
    int width = 0, height = 0, channels = 0;
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &width, &height, &channels, 4);
    if (!pixels) {
        (*errors)[image_index] = fmt::format("cannot decode it ({}; glTF images are PNG or JPEG)",
                                             stbi_failure_reason() ? stbi_failure_reason() : "unknown error");
        return true;  // fatal only if a material uses it
    }
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
    stbi_image_free(pixels);
    return true;
}

namespace {

constexpr const char* kEmissiveStrength = "KHR_materials_emissive_strength";

TextureWrap wrap_mode(int gl_wrap) {
    if (gl_wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::ClampToEdge;
    if (gl_wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::MirroredRepeat;
    return TextureWrap::Repeat;  // glTF's default, and what an unknown value falls back to
}

}  // namespace

GltfMaterials::GltfMaterials(const tinygltf::Model& model, const GltfImageErrors& image_errors,
                             const std::filesystem::path& path)
    : model_(model), image_errors_(image_errors), path_(path) {}

int GltfMaterials::checked_index(int material) const {
    if (material < -1 || material >= int(model_.materials.size()))
        throw_file_error(path_, "material index {} is out of range ({} materials)", material, model_.materials.size());
    return material;
}

int GltfMaterials::texcoord_set(int material) const {
    if (material < 0) return -1;
    const tinygltf::Material& source = model_.materials[size_t(material)];
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    const std::pair<const tinygltf::TextureInfo*, const char*> textures[] = {
        {&pbr.baseColorTexture, "baseColorTexture"},
        {&pbr.metallicRoughnessTexture, "metallicRoughnessTexture"},
        {&source.emissiveTexture, "emissiveTexture"}};
    int set = -1;
    const char* first = nullptr;
    for (const auto& [info, key] : textures) {
        if (info->index < 0) continue;
        if (info->texCoord < 0)
            throw_file_error(path_, "material '{}': {} texCoord {} is negative", name(material), key, info->texCoord);
        if (first && info->texCoord != set)
            throw_file_error(path_, "material '{}': {} reads TEXCOORD_{} and {} TEXCOORD_{}; rsl reads one set of "
                             "texture coordinates per material", name(material), first, set, key, info->texCoord);
        set = info->texCoord;
        first = key;
    }
    return set;
}

std::string GltfMaterials::name(int material) const {
    if (material < 0) return "default";
    const std::string& n = model_.materials[size_t(material)].name;
    return n.empty() ? fmt::format("material{}", material) : n;
}

int GltfMaterials::scene_material(int material, Scene& scene, int default_material) {
    if (material < 0) return default_material;
    if (auto it = scene_index_.find(material); it != scene_index_.end()) return it->second;
    MaterialDesc desc = convert(material);
    // Scene materials are looked up by name (part_materials, live edits): a
    // glTF name the scene file already uses gets the file's name appended.
    const auto taken = [&](const std::string& n) {
        for (const MaterialDesc& m : scene.materials)
            if (m.name == n) return true;
        return false;
    };
    if (taken(desc.name)) desc.name += " (" + path_.filename().string() + ")";
    for (int k = 2; taken(desc.name); ++k) desc.name = fmt::format("{} #{}", name(material), k);
    scene.materials.push_back(std::move(desc));
    return scene_index_[material] = int(scene.materials.size()) - 1;
}

MaterialDesc GltfMaterials::convert(int material) {
    const tinygltf::Material& source = model_.materials[size_t(material)];
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    const std::string what = fmt::format("material '{}'", name(material));
    MaterialDesc desc;
    desc.name = name(material);
    desc.model = "gltf_pbr";
    // tinygltf fills glTF's defaults (1, 1, 1) when the file leaves them out.
    if (pbr.baseColorFactor.size() != 4)
        throw_file_error(path_, "{}: baseColorFactor has {} values, not 4", what, pbr.baseColorFactor.size());
    const auto unit = [&](double x, const char* key) {
        if (!(x >= 0.0 && x <= 1.0)) throw_file_error(path_, "{}: {} must be in [0, 1] (got {})", what, key, x);
        return float(x);
    };
    desc.params["base_color"] = {unit(pbr.baseColorFactor[0], "baseColorFactor"),
                                 unit(pbr.baseColorFactor[1], "baseColorFactor"),
                                 unit(pbr.baseColorFactor[2], "baseColorFactor")};
    desc.params["metallic"] = {unit(pbr.metallicFactor, "metallicFactor")};
    desc.params["roughness"] = {unit(pbr.roughnessFactor, "roughnessFactor")};
    if (pbr.baseColorTexture.index >= 0)
        desc.base_color_texture = texture(pbr.baseColorTexture.index, what, "base colour", TextureEncoding::Srgb);
    if (pbr.metallicRoughnessTexture.index >= 0)
        desc.metallic_roughness_texture =
            texture(pbr.metallicRoughnessTexture.index, what, "metallic-roughness", TextureEncoding::Linear);
    read_emission(source, what, desc);

    if (source.normalTexture.index >= 0) ignored_.insert("normalTexture");
    if (source.occlusionTexture.index >= 0) ignored_.insert("occlusionTexture (rsl computes the occlusion itself)");
    if (source.alphaMode == "BLEND" || source.alphaMode == "MASK") ignored_.insert("alphaMode " + source.alphaMode);
    for (const auto& [extension, value] : source.extensions)
        if (extension != kEmissiveStrength) ignored_.insert(extension);
    return desc;
}

// emissiveFactor × KHR_materials_emissive_strength, and the emissiveTexture
// (sRGB-encoded, as base colour images are).
void GltfMaterials::read_emission(const tinygltf::Material& source, const std::string& what, MaterialDesc& desc) {
    // tinygltf fills glTF's default (0, 0, 0) when the file leaves it out.
    if (source.emissiveFactor.size() != 3)
        throw_file_error(path_, "{}: emissiveFactor has {} values, not 3", what, source.emissiveFactor.size());
    Color factor;
    for (int c = 0; c < 3; ++c) {
        const double x = source.emissiveFactor[size_t(c)];
        if (!(x >= 0.0 && x <= 1.0)) throw_file_error(path_, "{}: emissiveFactor must be in [0, 1] (got {})", what, x);
        factor[c] = float(x);
    }
    double strength = 1.0;
    if (auto it = source.extensions.find(kEmissiveStrength); it != source.extensions.end()) {
        const tinygltf::Value& extension = it->second;
        if (!extension.IsObject())
            throw_file_error(path_, "{}: {} is not an object", what, kEmissiveStrength);
        if (extension.Has("emissiveStrength")) {
            const tinygltf::Value& value = extension.Get("emissiveStrength");
            if (!value.IsNumber())
                throw_file_error(path_, "{}: {}.emissiveStrength is not a number", what, kEmissiveStrength);
            strength = value.GetNumberAsDouble();
        }
        if (!(strength >= 0.0 && strength <= double(kMaxEmission)))
            throw_file_error(path_, "{}: {}.emissiveStrength {} is not in [0, {:g}]", what, kEmissiveStrength,
                             strength, kMaxEmission);
    }
    desc.emissive = factor * float(strength);
    if (const std::string problem = emission_problem(desc.emissive); !problem.empty())
        throw_file_error(path_, "{}: emissiveFactor × emissiveStrength: {}", what, problem);
    if (source.emissiveTexture.index >= 0)
        desc.emissive_texture = texture(source.emissiveTexture.index, what, "emissive", TextureEncoding::Srgb);
}

std::shared_ptr<const Texture> GltfMaterials::texture(int texture_index, const std::string& what, const char* role,
                                                     TextureEncoding encoding) {
    const std::pair<int, TextureEncoding> key{texture_index, encoding};
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    if (size_t(texture_index) >= model_.textures.size())
        throw_file_error(path_, "{}: {} texture index {} is out of range ({} textures)", what, role, texture_index,
                         model_.textures.size());
    const tinygltf::Texture& source = model_.textures[size_t(texture_index)];
    if (source.source < 0 || size_t(source.source) >= model_.images.size())
        throw_file_error(path_, "{}: texture {} has no image in range (source {}, {} images)", what, texture_index,
                         source.source, model_.images.size());
    const tinygltf::Image& image = model_.images[size_t(source.source)];
    const std::string image_name = !image.name.empty() ? echo_value(image.name)
                                   : !image.uri.empty() && image.uri.substr(0, 5) != "data:"
                                       ? echo_value(image.uri)
                                       : fmt::format("image{}", source.source);
    if (auto e = image_errors_.find(source.source); e != image_errors_.end())
        throw_file_error(path_, "{}: {} image '{}': {}", what, role, image_name, echo_message(e->second));
    if (image.image.empty() || image.component != 4 || image.width < 1 || image.height < 1)
        throw_file_error(path_, "{}: {} image '{}' could not be read (missing file?)", what, role, image_name);

    auto texture = std::make_shared<Texture>();
    texture->name = image_name;
    if (source.sampler >= 0) {
        if (size_t(source.sampler) >= model_.samplers.size())
            throw_file_error(path_, "{}: texture {} sampler {} is out of range ({} samplers)", what, texture_index,
                             source.sampler, model_.samplers.size());
        texture->wrap_s = wrap_mode(model_.samplers[size_t(source.sampler)].wrapS);
        texture->wrap_t = wrap_mode(model_.samplers[size_t(source.sampler)].wrapT);
        if (model_.samplers[size_t(source.sampler)].magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST)
            texture->filter = TextureFilter::Nearest;
    }
    // glTF colour images (base colour, emissive) are sRGB-encoded, data images (metallic-roughness)
    // linear; the renderer works in linear RGB.
    std::array<float, 256> decoded;
    for (int v = 0; v < 256; ++v)
        decoded[size_t(v)] = encoding == TextureEncoding::Srgb ? srgb_to_linear(float(v) / 255.0f) : float(v) / 255.0f;
    texture->image = Image(image.width, image.height, 3);
    for (size_t p = 0; p < size_t(image.width) * size_t(image.height); ++p)
        for (int c = 0; c < 3; ++c) texture->image.pixels[3 * p + size_t(c)] = decoded[image.image[4 * p + size_t(c)]];
    return textures_[key] = std::move(texture);
}

void GltfMaterials::warn_ignored() const {
    if (ignored_.empty()) return;
    std::string list;
    for (const std::string& what : ignored_) list += (list.empty() ? "" : ", ") + what;
    warn_file(path_, "materials: ignored (rsl honours base colour, metallic, roughness, baseColorTexture, "
              "metallicRoughnessTexture and emission): {}", list);
}

}  // namespace rsl
