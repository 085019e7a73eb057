#include "src/formats/gltf_skins.h"

#include <cmath>

#include "src/core/error.h"

namespace rsl::gltf {

int import_skin(const tinygltf::Model& model, const std::filesystem::path& path, const AccessorReader& reader,
                const SceneNodes& nodes, int skin_index, Scene& scene) {
    if (skin_index < 0 || size_t(skin_index) >= model.skins.size())
        throw_file_error(path, "skin index {} is out of range ({} skins)", skin_index, model.skins.size());
    const tinygltf::Skin& source = model.skins[size_t(skin_index)];
    const std::string what = fmt::format("skin {}", skin_index);
    if (source.joints.empty()) throw_file_error(path, "{} has no joints", what);
    if (source.joints.size() > 65536) throw_file_error(path, "{} has {} joints (at most 65536)", what, source.joints.size());
    Skin skin;
    skin.name = source.name.empty() ? fmt::format("skin{}", skin_index) : source.name;
    for (size_t j = 0; j < source.joints.size(); ++j) {
        const int n = source.joints[j];
        if (n < 0 || size_t(n) >= model.nodes.size())
            throw_file_error(path, "{}: joint {} is node {}, out of range ({} nodes)", what, j, n, model.nodes.size());
        if (nodes.scene_node[size_t(n)] < 0)
            throw_file_error(path, "{}: joint {} (node {}) is not in the default scene", what, j, n);
        skin.joints.push_back(nodes.scene_node[size_t(n)]);
    }
    skin.inverse_bind.assign(source.joints.size(), Mat4(1.0f));
    if (source.inverseBindMatrices >= 0) {
        const std::vector<float> values =
            reader.floats(source.inverseBindMatrices, TINYGLTF_TYPE_MAT4, what + " inverseBindMatrices");
        if (values.size() != 16 * source.joints.size())
            throw_file_error(path, "{}: {} inverse bind matrices for {} joints", what, values.size() / 16,
                             source.joints.size());
        for (size_t j = 0; j < source.joints.size(); ++j) {
            Mat4& m = skin.inverse_bind[j];
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = values[16 * j + size_t(4 * c + r)];  // column-major, as glm
            const float det = glm::determinant(Mat3(m));
            bool finite = true;
            for (int k = 0; k < 16; ++k) finite = finite && std::isfinite(values[16 * j + size_t(k)]);
            if (!finite || !(std::abs(det) > 1e-12f))
                throw_file_error(path, "{}: inverse bind matrix {} is not finite and invertible", what, j);
        }
    }
    scene.skins.push_back(std::move(skin));
    return int(scene.skins.size()) - 1;
}

}  // namespace rsl::gltf
