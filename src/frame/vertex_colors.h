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
//   P ×      { string part name, u64 vertex count }
//   f32 ×3   RGB per vertex, parts in order, vertices in mesh order
//   u64      FNV-1a 64 checksum of every preceding byte
//
// Files are written atomically; a reader refuses foreign files (magic), other
// versions, truncated or corrupt files (size, checksum) and non-finite values,
// naming the file and the problem.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "src/core/math.h"

namespace rsl {

inline constexpr uint32_t kVertexColorsVersion = 1;

struct VertexColors {
    std::string scene_name;
    std::string producer;
    float time = 0;
    std::vector<std::string> part_names;
    std::vector<std::vector<Color>> parts;  // parts[p][v]: RGB of vertex v of part p

    size_t vertex_count() const;
    // Adds a part of `vertices` black vertices.
    void add_part(const std::string& name, size_t vertices);
};

void write_vertex_colors(const std::filesystem::path& path, const VertexColors& colors);
VertexColors read_vertex_colors(const std::filesystem::path& path);

// Throws rsl::Error naming both files when `a` and `b` do not describe the same
// vertices (scene name, part count, part names, per-part vertex counts).
void check_same_vertices(const VertexColors& a, const std::filesystem::path& path_a, const VertexColors& b,
                         const std::filesystem::path& path_b);

}  // namespace rsl
