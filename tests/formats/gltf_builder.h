#pragma once
// Writes glTF files by hand (JSON + one binary buffer), independently of the
// loader under test (tests/formats/gltf_test.cpp; the instancing tests use it for
// a mesh shared by several nodes). By hand rather than through tinygltf's
// writer because tinygltf 2.7 cannot write sparse accessors; everything else
// (scenes, cameras, KHR_lights_punctual, skins) is plain JSON through doc().
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rsl::test {

class GltfBuilder {
public:
    using Json = nlohmann::json;

    GltfBuilder() {
        doc_["asset"] = {{"version", "2.0"}, {"generator", "rsl gltf_test"}};
        for (const char* key : {"accessors", "bufferViews", "meshes", "nodes", "animations"}) doc_[key] = Json::array();
    }

    int floats(const std::vector<float>& data, const char* type) {
        return accessor(data.data(), data.size() * sizeof(float), 5126, data.size() / components(type), type);
    }
    int indices(const std::vector<uint32_t>& data) { return accessor(data.data(), data.size() * 4, 5125, data.size(), "SCALAR"); }

    // A sparse float accessor of `count` elements: `base` (none: zeros, no
    // buffer view) with `values` at `sparse_indices` (stored as uint16, as
    // exporters write small index sets).
    int sparse_floats(const std::vector<float>& base, size_t count, const char* type,
                      const std::vector<uint16_t>& sparse_indices, const std::vector<float>& values) {
        int a;
        if (base.empty()) {
            doc_["accessors"].push_back({{"componentType", 5126}, {"count", count}, {"type", type}});
            a = int(doc_["accessors"].size()) - 1;
        } else {
            a = floats(base, type);
        }
        const int index_view = view(sparse_indices.data(), sparse_indices.size() * 2);
        const int value_view = view(values.data(), values.size() * 4);
        doc_["accessors"][a]["sparse"] = {{"count", sparse_indices.size()},
                                          {"indices", {{"bufferView", index_view}, {"componentType", 5123}}},
                                          {"values", {{"bufferView", value_view}}}};
        return a;
    }

    // A mesh from positions (flat xyz), optional normals and indices.
    int mesh(const std::vector<float>& positions, const std::vector<uint32_t>& corner_indices,
             const std::vector<float>& normals = {}) {
        Json primitive = {{"attributes", {{"POSITION", floats(positions, "VEC3")}}}, {"mode", 4}};
        if (!normals.empty()) primitive["attributes"]["NORMAL"] = floats(normals, "VEC3");
        if (!corner_indices.empty()) primitive["indices"] = indices(corner_indices);
        doc_["meshes"].push_back({{"primitives", Json::array({primitive})}});
        return int(doc_["meshes"].size()) - 1;
    }

    int node(Json node) {
        doc_["nodes"].push_back(std::move(node));
        return int(doc_["nodes"].size()) - 1;
    }

    // One channel in one animation (each channel gets its own sampler).
    void channel(int node, const char* path, const char* interpolation, const std::vector<float>& times,
                 const std::vector<float>& values) {
        if (doc_["animations"].empty()) doc_["animations"].push_back({{"channels", Json::array()}, {"samplers", Json::array()}});
        Json& animation = doc_["animations"][0];
        const char* type = std::string(path) == "rotation" ? "VEC4" : "VEC3";
        animation["samplers"].push_back(
            {{"input", floats(times, "SCALAR")}, {"output", floats(values, type)}, {"interpolation", interpolation}});
        animation["channels"].push_back(
            {{"sampler", animation["samplers"].size() - 1}, {"target", {{"node", node}, {"path", path}}}});
    }

    Json& doc() { return doc_; }

    void write_gltf(const std::filesystem::path& path) {
        const std::string bin_name = path.stem().string() + ".bin";
        std::ofstream(path.parent_path() / bin_name, std::ios::binary).write(reinterpret_cast<const char*>(bin_.data()), bin_.size());
        Json doc = doc_;
        doc["buffers"] = Json::array({{{"uri", bin_name}, {"byteLength", bin_.size()}}});
        std::ofstream(path) << doc.dump(1);
    }

    void write_glb(const std::filesystem::path& path) {
        Json doc = doc_;
        doc["buffers"] = Json::array({{{"byteLength", bin_.size()}}});
        std::string json = doc.dump();
        while (json.size() % 4) json += ' ';
        std::vector<uint8_t> bin = bin_;
        while (bin.size() % 4) bin.push_back(0);
        std::ofstream out(path, std::ios::binary);
        auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
        out.write("glTF", 4);
        u32(2);
        u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
        u32(uint32_t(json.size()));
        u32(0x4E4F534A);  // "JSON"
        out.write(json.data(), json.size());
        u32(uint32_t(bin.size()));
        u32(0x004E4942);  // "BIN\0"
        out.write(reinterpret_cast<const char*>(bin.data()), bin.size());
    }

private:
    static size_t components(const std::string& type) {
        return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "MAT4" ? 16 : 4;
    }

    int view(const void* data, size_t bytes) {
        while (bin_.size() % 4) bin_.push_back(0);
        const size_t offset = bin_.size();
        bin_.resize(offset + bytes);
        std::memcpy(bin_.data() + offset, data, bytes);
        doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
        return int(doc_["bufferViews"].size()) - 1;
    }

    int accessor(const void* data, size_t bytes, int component_type, size_t count, const char* type) {
        doc_["accessors"].push_back({{"bufferView", view(data, bytes)},
                                     {"componentType", component_type},
                                     {"count", count},
                                     {"type", type}});
        return int(doc_["accessors"].size()) - 1;
    }

    Json doc_;
    std::vector<uint8_t> bin_;
};

}  // namespace rsl::test
