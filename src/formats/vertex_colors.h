#pragma once
// Per-vertex RGB results of a renderer (the ground truth, the RSL renderer) and
// their file, `.rslv`, which `rsl compare` reads. Layout (little-endian):
//
//   8 bytes  magic "RSLVTXC\0"
//   u32      version (kVertexColorsVersion)
//   string   scene name          (u32 byte count, then UTF-8 bytes)
//   string   producer            (e.g. "truth", "rsl-cpu")
//   f32      time (seconds)
//   u32      part count P
//   P ×      { string part name, u64 vertex count [, u8 layered (version 2)] }
//   f32 ×3   RGB per vertex, parts in order, vertices in mesh order
//   f32 ×3   version 2: the specular layer per vertex of every layered part, in order
//   u64      FNV-1a 64 checksum of every preceding byte
//
// Textured parts (a base colour texture, docs/design/RENDERER.md "Textures") are
// layered: `parts` holds their diffuse sum at unit texture and `specular`
// the specular sum; an image multiplies the first by the texture per pixel.
// Files without layered parts are written as version 1, as before.
// Files are written atomically; a reader refuses foreign files (magic), other
// versions, truncated or corrupt files (size, checksum) and non-finite values,
// naming the file and the problem.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "src/core/math.h"
#include "src/core/texture.h"

namespace rsl {

inline constexpr uint32_t kVertexColorsVersion = 2;  // reads 1 and 2

struct VertexColors {
    std::string scene_name;
    std::string producer;
    float time = 0;
    std::vector<std::string> part_names;
    std::vector<std::vector<Color>> parts;  // parts[p][v]: RGB of vertex v of part p
    // specular[p]: empty, or (layered part) the specular sum of each vertex,
    // parts[p] then being the diffuse sum at unit texture. Same size as parts.
    std::vector<std::vector<Color>> specular;
    // The base colour texture of each layered part, for image formation (not
    // stored in .rslv files: form_image then takes the scene's).
    std::vector<std::shared_ptr<const Texture>> textures;
    // The emission each part's colours include (the specular layer's, for a
    // layered part), for image formation, which takes a textured emission per
    // pixel (docs/design/RENDERER.md "Emission"). Not stored in .rslv files:
    // empty, form_image takes the scene's materials'.
    struct PartEmission {
        Color emissive{0};
        std::shared_ptr<const Texture> texture;
    };
    std::vector<PartEmission> emission;

    size_t vertex_count() const;
    bool layered(size_t part) const { return part < specular.size() && !specular[part].empty(); }
    // Adds a part of `vertices` black vertices, layered when `texture` is set.
    void add_part(const std::string& name, size_t vertices, std::shared_ptr<const Texture> texture = nullptr);
    // Adds one emission a vertex to part `part`: to its specular layer when
    // layered (the base colour texture does not scale emission), else to its colours.
    void add_emission(size_t part, const std::vector<Color>& emission);
    // The colours at unit texture: each layered part's diffuse + specular, no layers.
    VertexColors at_unit_texture() const;
};

void write_vertex_colors(const std::filesystem::path& path, const VertexColors& colors);
VertexColors read_vertex_colors(const std::filesystem::path& path);

// Throws rsl::Error naming both files when `a` and `b` do not describe the same
// vertices (scene name, part count, part names, per-part vertex counts).
void check_same_vertices(const VertexColors& a, const std::filesystem::path& path_a, const VertexColors& b,
                         const std::filesystem::path& path_b);

}  // namespace rsl
