// Reader and writer of .rslv per-vertex colour files (format in vertex_colors.h).
#include "src/formats/vertex_colors.h"

#include <cmath>
#include <cstring>

#include "src/core/atomic_file.h"
#include "src/formats/binary_io.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"

namespace rsl {

namespace {

constexpr char kMagic[8] = {'R', 'S', 'L', 'V', 'T', 'X', 'C', '\0'};
static_assert(sizeof(Color) == 3 * sizeof(float), "Color must be three packed floats");

}  // namespace

size_t VertexColors::vertex_count() const {
    size_t total = 0;
    for (const auto& part : parts) total += part.size();
    return total;
}

void VertexColors::add_part(const std::string& name, size_t vertices, std::shared_ptr<const Texture> texture) {
    part_names.push_back(name);
    parts.emplace_back(vertices, Color(0));
    specular.resize(parts.size());
    textures.resize(parts.size());
    if (texture) specular.back().assign(vertices, Color(0));
    textures.back() = std::move(texture);
}

void VertexColors::add_emission(size_t part, const std::vector<Color>& emission) {
    std::vector<Color>& layer = layered(part) ? specular[part] : parts[part];
    RSL_CHECK_EQ(layer.size(), emission.size());
    for (size_t v = 0; v < layer.size(); ++v) layer[v] += emission[v];
}

VertexColors VertexColors::at_unit_texture() const {
    VertexColors folded = *this;
    for (size_t p = 0; p < parts.size(); ++p)
        if (layered(p))
            for (size_t v = 0; v < parts[p].size(); ++v) folded.parts[p][v] += specular[p][v];
    folded.specular.assign(parts.size(), {});
    folded.textures.assign(parts.size(), nullptr);
    return folded;
}

void write_vertex_colors(const std::filesystem::path& path, const VertexColors& colors) {
    RSL_CHECK_EQ(colors.part_names.size(), colors.parts.size());
    bool any_layered = false;
    for (size_t p = 0; p < colors.parts.size(); ++p) {
        if (colors.layered(p)) RSL_CHECK_EQ(colors.specular[p].size(), colors.parts[p].size());
        any_layered = any_layered || colors.layered(p);
    }
    // The reader refuses non-finite values: such a file would be written only to be refused.
    const auto check_finite = [&](const std::vector<Color>& values, size_t p, const char* what) {
        for (size_t v = 0; v < values.size(); ++v)
            if (!std::isfinite(values[v].r) || !std::isfinite(values[v].g) || !std::isfinite(values[v].b))
                throw_file_error(path, "cannot write the non-finite {} ({}, {}, {}) of part '{}' vertex {}; nothing "
                                 "written", what, values[v].r, values[v].g, values[v].b, colors.part_names[p], v);
    };
    for (size_t p = 0; p < colors.parts.size(); ++p) {
        check_finite(colors.parts[p], p, "colour");
        if (colors.layered(p)) check_finite(colors.specular[p], p, "specular colour");
    }
    BinaryWriter w;
    w.put_bytes(kMagic, sizeof(kMagic));
    w.put(any_layered ? kVertexColorsVersion : uint32_t(1));
    w.put_string(colors.scene_name);
    w.put_string(colors.producer);
    w.put(colors.time);
    w.put(uint32_t(colors.parts.size()));
    for (size_t p = 0; p < colors.parts.size(); ++p) {
        w.put_string(colors.part_names[p]);
        w.put(uint64_t(colors.parts[p].size()));
        if (any_layered) w.put(uint8_t(colors.layered(p)));
    }
    for (const auto& part : colors.parts) w.put_bytes(part.data(), part.size() * sizeof(Color));
    for (size_t p = 0; p < colors.parts.size(); ++p)
        if (colors.layered(p)) w.put_bytes(colors.specular[p].data(), colors.specular[p].size() * sizeof(Color));
    write_file_atomically(path, w.finish_with_checksum());
}

VertexColors read_vertex_colors(const std::filesystem::path& path) {
    const std::string bytes =
        read_bounded_file(path, kMaxVertexColorsFileBytes, "a vertex-colour file", std::string_view(kMagic, sizeof(kMagic)),
                          "not an rsl vertex-colour file (.rslv): wrong magic number");
    const size_t header_and_data = bytes.size() >= sizeof(kMagic) + 12 ? bytes.size() - sizeof(uint64_t) : 0;
    BinaryReader r(path, bytes, header_and_data);
    char magic[sizeof(kMagic)];
    r.get_bytes(magic, sizeof(magic), "magic number");
    const uint32_t version = r.get<uint32_t>("version");
    if (version != 1 && version != kVertexColorsVersion)
        throw_file_error(path, "vertex-colour file version {}, this build reads versions 1 to {}", version,
                         kVertexColorsVersion);
    if (!has_valid_checksum(bytes))
        throw_file_error(path, "checksum mismatch: the file is corrupt or truncated");

    VertexColors colors;
    colors.scene_name = r.get_string("scene name");
    colors.producer = r.get_string("producer");
    colors.time = r.get<float>("time");
    const uint32_t part_count = r.get<uint32_t>("part count");
    std::vector<uint64_t> counts;
    std::vector<bool> layered;
    uint64_t total = 0;
    for (uint32_t p = 0; p < part_count; ++p) {
        colors.part_names.push_back(r.get_string("part name"));
        counts.push_back(r.get<uint64_t>("vertex count"));
        const uint8_t flag = version >= 2 ? r.get<uint8_t>("layered flag") : 0;
        if (flag > 1) throw_file_error(path, "corrupt: part '{}' has layered flag {}", colors.part_names.back(), flag);
        layered.push_back(flag == 1);
        // Compared before they are added: a count near 2^64 would wrap when
        // doubled for its two layers. total ≤ remaining holds, so this also
        // guards the multiplication below.
        const uint64_t layers = flag ? 2 : 1;
        if (counts.back() > (r.remaining() - total) / layers)
            throw_file_error(path, "corrupt: part '{}' has {} vertices{}, which do not fit in the file",
                             colors.part_names.back(), counts.back(), flag ? " in two layers" : "");
        total += counts.back() * layers;
    }
    if (total * sizeof(Color) != r.remaining())
        throw_file_error(path, "corrupt: header says {} vertices ({} bytes of data), file holds {} bytes", total,
                         total * sizeof(Color), r.remaining());
    const auto read_layer = [&](std::vector<Color>& values, uint32_t p, const char* what) {
        r.get_bytes(values.data(), values.size() * sizeof(Color), what);
        for (size_t v = 0; v < values.size(); ++v)
            if (!std::isfinite(values[v].r) || !std::isfinite(values[v].g) || !std::isfinite(values[v].b))
                throw_file_error(path, "non-finite {} at part '{}' vertex {}", what, colors.part_names[p], v);
    };
    colors.specular.resize(part_count);
    colors.textures.resize(part_count);
    for (uint32_t p = 0; p < part_count; ++p) read_layer(colors.parts.emplace_back(counts[p]), p, "colour");
    for (uint32_t p = 0; p < part_count; ++p)
        if (layered[p]) read_layer(colors.specular[p] = std::vector<Color>(counts[p]), p, "specular colour");
    return colors;
}

void check_same_vertices(const VertexColors& a, const std::filesystem::path& path_a, const VertexColors& b,
                         const std::filesystem::path& path_b) {
    auto mismatch = [&](const std::string& what) {
        throw_error("{} and {} are not comparable: {}", path_a.string(), path_b.string(), what);
    };
    if (a.scene_name != b.scene_name) mismatch(fmt::format("scenes '{}' vs '{}'", a.scene_name, b.scene_name));
    if (a.parts.size() != b.parts.size())
        mismatch(fmt::format("{} parts vs {} parts", a.parts.size(), b.parts.size()));
    for (size_t p = 0; p < a.parts.size(); ++p) {
        if (a.part_names[p] != b.part_names[p])
            mismatch(fmt::format("part {} is '{}' vs '{}'", p, a.part_names[p], b.part_names[p]));
        if (a.layered(p) != b.layered(p))
            mismatch(fmt::format("part '{}' is layered (textured) in one and not the other", a.part_names[p]));
        if (a.parts[p].size() != b.parts[p].size())
            mismatch(fmt::format("part '{}' has {} vs {} vertices", a.part_names[p], a.parts[p].size(),
                                 b.parts[p].size()));
    }
    if (std::abs(a.time - b.time) > 1e-6f * std::max(1.0f, std::abs(b.time)))
        mismatch(fmt::format("times {} s vs {} s", a.time, b.time));
}

}  // namespace rsl
