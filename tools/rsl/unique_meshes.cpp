#include "tools/rsl/unique_meshes.h"

#include <filesystem>

#include <fmt/format.h>

namespace rsl::cli {
namespace {

std::string megabytes(size_t bytes) {
    return bytes < 100000 ? fmt::format("{:.1f} kB", double(bytes) / 1e3) : fmt::format("{:.2f} MB", double(bytes) / 1e6);
}

std::string outcome_text(const FieldOutcome& o) {
    const std::string name = o.file.filename().string();
    switch (o.state) {
        case FieldState::Baked:
            return fmt::format("{} baked in {:.2f} s, {} on disk, {} in RAM", name, o.seconds, megabytes(o.disk_bytes),
                               megabytes(o.memory_bytes));
        case FieldState::Reused:
            return fmt::format("{} read in {:.2f} s, {} on disk, {} in RAM", name, o.seconds, megabytes(o.disk_bytes),
                               megabytes(o.memory_bytes));
        case FieldState::Skipped: break;
    }
    if (o.wanted) {  // a plan: what the cache holds (not verified; `rsl info FILE.rslf` does)
        std::error_code ec;
        const auto bytes = std::filesystem::file_size(o.file, ec);
        return ec ? fmt::format("{} not in the cache", name) : fmt::format("{} in the cache, {}", name, megabytes(bytes));
    }
    return fmt::format("{} left to another shard", name);
}

}  // namespace

void print_unique_meshes(std::FILE* out, const Scene& scene, const SceneFields& fields) {
    size_t disk = 0, memory = 0;
    for (const UniqueFields& u : fields.unique) {
        const Part& first = scene.parts[size_t(u.mesh.parts.front())];
        std::string names;
        constexpr size_t kNamesShown = 4;
        for (size_t i = 0; i < u.mesh.parts.size() && i < kNamesShown; ++i)
            names += fmt::format("{}{}", i ? ", " : "", scene.parts[size_t(u.mesh.parts[i])].name);
        if (u.mesh.parts.size() > kNamesShown) names += fmt::format(", ... ({} more)", u.mesh.parts.size() - kNamesShown);
        fmt::print(out, "    mesh {:016x} '{}': {} vertices, {} part{} ({})\n", u.mesh.mesh_hash, first.name,
                   first.mesh.vertex_count(), u.mesh.parts.size(), u.mesh.parts.size() == 1 ? "" : "s", names);
        for (const auto& [kind, o] : {std::pair{"SVDF", &u.svdf_outcome}, std::pair{"OVDF", &u.ovdf_outcome}}) {
            if (o->file.empty()) continue;
            fmt::print(out, "      {} {}\n", kind, outcome_text(*o));
            disk += o->disk_bytes;
            memory += o->memory_bytes;
        }
    }
    if (disk || memory)
        fmt::print(out, "    fields: {} on disk, {} in RAM for {} parts (one copy per unique mesh)\n", megabytes(disk),
                   megabytes(memory), scene.parts.size());
}

}  // namespace rsl::cli
