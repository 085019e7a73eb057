// Wavefront OBJ reader: positions, normals and faces (texture coordinates are
// read past and ignored). Errors name the file and line.
#include <charconv>
#include <cmath>
#include <string_view>
#include <unordered_map>

#include "src/core/error.h"
#include "src/formats/file_reading.h"
#include "src/core/mesh.h"
#include "src/formats/obj_loader.h"

namespace rsl {

namespace {

class ObjParser {
public:
    explicit ObjParser(const std::filesystem::path& path) : path_(path) {}

    TriangleMesh parse(std::string_view text) {
        mesh_.name = path_.stem().string();
        size_t begin = 0;
        while (begin < text.size()) {
            size_t end = text.find('\n', begin);
            if (end == std::string_view::npos) end = text.size();
            ++line_number_;
            parse_line(text.substr(begin, end - begin));
            begin = end + 1;
        }
        if (mesh_.indices.empty())
            throw_file_error(path_, "no faces ({} vertex positions): empty mesh", positions_.size());
        if (!any_normal_) mesh_.normals.clear();  // let validation compute them all
        return std::move(mesh_);
    }

private:
    static constexpr int kNoNormal = -1;

    [[noreturn]] void fail(std::string_view what) const {
        throw_file_error(path_, "line {}: {}", line_number_, what);
    }

    static std::string_view next_token(std::string_view& rest) {
        size_t start = rest.find_first_not_of(" \t\r");
        if (start == std::string_view::npos) {
            rest = {};
            return {};
        }
        size_t stop = rest.find_first_of(" \t\r", start);
        if (stop == std::string_view::npos) stop = rest.size();
        std::string_view token = rest.substr(start, stop - start);
        rest = rest.substr(stop);
        return token;
    }

    float parse_float(std::string_view token) const {
        float value = 0;
        auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size())
            fail(fmt::format("'{}' is not a number", token));
        if (!std::isfinite(value)) fail(fmt::format("coordinate '{}' is not finite", token));
        return value;
    }

    Vec3 parse_vec3(std::string_view rest, const char* what) const {
        Vec3 v;
        for (int k = 0; k < 3; ++k) {
            std::string_view token = next_token(rest);
            if (token.empty()) fail(fmt::format("{} needs 3 coordinates", what));
            v[k] = parse_float(token);
        }
        return v;
    }

    // OBJ indices are 1-based; negative ones count back from the latest element.
    int resolve_index(std::string_view token, size_t count, const char* what) const {
        long value = 0;
        auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size())
            fail(fmt::format("bad {} index '{}'", what, token));
        const long resolved = value > 0 ? value - 1 : long(count) + value;
        if (value == 0 || resolved < 0 || resolved >= long(count))
            fail(fmt::format("{} index {} is out of range ({} defined so far)", what, value, count));
        return int(resolved);
    }

    // One face corner "v", "v/t", "v//n" or "v/t/n" → mesh vertex index.
    uint32_t parse_corner(std::string_view corner) {
        const size_t slash1 = corner.find('/');
        const int position = resolve_index(corner.substr(0, slash1), positions_.size(), "vertex");
        int normal = kNoNormal;
        if (slash1 != std::string_view::npos) {
            const size_t slash2 = corner.find('/', slash1 + 1);
            if (slash2 != std::string_view::npos && slash2 + 1 < corner.size())
                normal = resolve_index(corner.substr(slash2 + 1), normals_.size(), "normal");
        }
        // Vertices are shared between faces unless their normals differ.
        const uint64_t key = (uint64_t(uint32_t(position)) << 32) | uint32_t(normal);
        auto [it, inserted] = vertex_of_.try_emplace(key, uint32_t(mesh_.positions.size()));
        if (inserted) {
            mesh_.positions.push_back(positions_[position]);
            // A corner without a normal gets a zero one: validation fills it in.
            mesh_.normals.push_back(normal == kNoNormal ? Vec3(0) : normals_[normal]);
            any_normal_ |= normal != kNoNormal;
        }
        return it->second;
    }

    void parse_face(std::string_view rest) {
        corners_.clear();
        for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest))
            corners_.push_back(parse_corner(token));
        if (corners_.size() < 3) fail(fmt::format("a face needs at least 3 vertices, this one has {}", corners_.size()));
        for (size_t k = 1; k + 1 < corners_.size(); ++k) {  // fan triangulation
            mesh_.indices.push_back(corners_[0]);
            mesh_.indices.push_back(corners_[k]);
            mesh_.indices.push_back(corners_[k + 1]);
        }
    }

    void parse_line(std::string_view line) {
        if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        std::string_view rest = line;
        const std::string_view keyword = next_token(rest);
        if (keyword == "v") {
            positions_.push_back(parse_vec3(rest, "a vertex"));  // optional w / colours are ignored
        } else if (keyword == "vn") {
            normals_.push_back(parse_vec3(rest, "a normal"));
        } else if (keyword == "f") {
            parse_face(rest);
        } else if (keyword == "o" && mesh_.indices.empty()) {
            std::string_view name = next_token(rest);
            if (!name.empty()) mesh_.name = std::string(name);
        }
        // vt, g, s, usemtl, mtllib, l, p, ...: not geometry this renderer uses.
    }

    std::filesystem::path path_;
    size_t line_number_ = 0;
    std::vector<Vec3> positions_, normals_;
    std::unordered_map<uint64_t, uint32_t> vertex_of_;
    std::vector<uint32_t> corners_;
    TriangleMesh mesh_;
    bool any_normal_ = false;
};

}  // namespace

TriangleMesh load_obj(const std::filesystem::path& path) {
    // Checked as each piece arrives: a binary or sparse file stops at its first megabyte.
    const auto refuse_nul = [&path](std::string_view piece, uint64_t offset) {
        if (const size_t nul = piece.find('\0'); nul != std::string_view::npos)
            throw_file_error(path, "contains NUL bytes (the first at byte {}): not a text OBJ file", offset + nul);
    };
    const std::string text = read_bounded_file(path, kMaxObjFileBytes, "an OBJ file", {}, {}, refuse_nul);
    TriangleMesh mesh = ObjParser(path).parse(text);
    if (const size_t dropped = validate_and_complete(mesh, path))
        warn_file(path, "{} degenerate triangle{} dropped", dropped, dropped == 1 ? "" : "s");
    return mesh;
}

}  // namespace rsl
