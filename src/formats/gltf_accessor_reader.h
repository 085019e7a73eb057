#pragma once
// Internal to the glTF loader (gltf_loader.cpp): reads a file's accessors,
// sparse ones included, into flat arrays, checking every index, count, stride
// and byte range first, so that a corrupt file gives an rsl::Error naming it.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <vector>

#include "src/core/error.h"
#include "src/formats/gltf_model.h"

namespace rsl::gltf {

inline int component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT4: return 16;  // a skin's inverse bind matrices
        default: return 0;
    }
}

// Reads checked accessors into flat arrays.
class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& model, const std::filesystem::path& path) : model_(model), path_(path) {}

    // Components as floats (integer components are normalized when the
    // accessor says so, as glTF specifies).
    std::vector<float> floats(int accessor_index, int expected_type, const std::string& what) const {
        const Range r = checked_range(accessor_index, what);
        const tinygltf::Accessor& a = model_.accessors[accessor_index];
        if (a.type != expected_type)
            throw_file_error(path_, "{}: accessor {} has {} components per element, expected {}", what, accessor_index,
                             component_count(a.type), component_count(expected_type));
        const int n = component_count(a.type);
        std::vector<float> out(a.count * n);
        for (size_t e = 0; e < a.count; ++e) {
            const unsigned char* element = r.data + e * r.stride;
            for (int c = 0; c < n; ++c) out[e * n + c] = read_float(element + c * r.component_size, a);
        }
        return out;
    }

    std::vector<uint32_t> indices(int accessor_index, const std::string& what) const {
        const Range r = checked_range(accessor_index, what);
        const tinygltf::Accessor& a = model_.accessors[accessor_index];
        if (a.type != TINYGLTF_TYPE_SCALAR) throw_file_error(path_, "{}: index accessor {} is not SCALAR", what, accessor_index);
        std::vector<uint32_t> out(a.count);
        for (size_t e = 0; e < a.count; ++e) {
            const unsigned char* p = r.data + e * r.stride;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[e] = *p; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: out[e] = load<uint16_t>(p); break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: out[e] = load<uint32_t>(p); break;
                default:
                    throw_file_error(path_, "{}: index accessor {} has component type {}, not an unsigned integer",
                                     what, accessor_index, a.componentType);
            }
        }
        return out;
    }

    size_t count(int accessor_index, const std::string& what) const {
        check_accessor_index(accessor_index, what);
        return model_.accessors[accessor_index].count;
    }

private:
    struct Range {
        const unsigned char* data = nullptr;  // first element
        size_t stride = 0, component_size = 0;
        std::vector<unsigned char> dense;  // a sparse accessor's elements, when `data` points here
    };

    // Zero-filled elements (a sparse accessor without a buffer view) beyond
    // this are a corrupt count, not a mesh: refused before allocating.
    static constexpr size_t kMaxDenseBytes = size_t(1) << 30;

    template <typename T>
    static T load(const unsigned char* p) {
        T value;
        std::memcpy(&value, p, sizeof(T));
        return value;
    }

    float read_float(const unsigned char* p, const tinygltf::Accessor& a) const {
        const bool norm = a.normalized;
        switch (a.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                const float v = float(load<int8_t>(p));
                return norm ? std::max(v / 127.0f, -1.0f) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
                const float v = float(*p);
                return norm ? v / 255.0f : v;
            }
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                const float v = float(load<int16_t>(p));
                return norm ? std::max(v / 32767.0f, -1.0f) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                const float v = float(load<uint16_t>(p));
                return norm ? v / 65535.0f : v;
            }
            default: return std::numeric_limits<float>::quiet_NaN();  // refused in checked_range
        }
    }

    void check_accessor_index(int accessor_index, const std::string& what) const {
        if (accessor_index < 0 || size_t(accessor_index) >= model_.accessors.size())
            throw_file_error(path_, "{}: accessor index {} is out of range ({} accessors)", what, accessor_index,
                             model_.accessors.size());
    }

    // The bytes of `count` elements of `element_size` from `byte_offset` in
    // buffer view `view_index` (tightly packed unless the view has a stride,
    // when `strided`), after checking that the view and its buffer exist and
    // that every element lies inside them. Returns the first element and the stride.
    std::pair<const unsigned char*, size_t> checked_view(int view_index, size_t byte_offset, size_t count,
                                                         size_t element_size, bool strided,
                                                         const std::string& where) const {
        if (view_index < 0 || size_t(view_index) >= model_.bufferViews.size())
            throw_file_error(path_, "{}: buffer view {} is out of range ({} views)", where, view_index,
                             model_.bufferViews.size());
        const tinygltf::BufferView& view = model_.bufferViews[view_index];
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
            throw_file_error(path_, "{}: buffer {} is out of range ({} buffers)", where, view.buffer, model_.buffers.size());
        const std::vector<unsigned char>& buffer = model_.buffers[view.buffer].data;
        if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
            throw_file_error(path_, "{}: buffer view {} (bytes {}..{}) overruns buffer {} of {} bytes", where,
                             view_index, view.byteOffset, view.byteOffset + view.byteLength, view.buffer,
                             buffer.size());
        const size_t stride = strided && view.byteStride ? view.byteStride : element_size;
        if (stride < element_size) throw_file_error(path_, "{}: byte stride {} < element size {}", where, stride, element_size);
        // Without multiplying: a count near 2^64 / stride would wrap around
        // and pass (std::vector then refused the size: an internal error).
        if (byte_offset > view.byteLength || element_size > view.byteLength - byte_offset ||
            count - 1 > (view.byteLength - byte_offset - element_size) / stride)
            throw_file_error(path_, "{}: {} elements from byte {} overrun buffer view {} of {} bytes", where, count,
                             byte_offset, view_index, view.byteLength);
        return {buffer.data() + view.byteOffset + byte_offset, stride};
    }

    // The accessor's bytes, after checking that accessor, buffer view and
    // buffer exist and that every element lies inside them. A sparse
    // accessor's elements are its base (zeros without a buffer view) with
    // the sparse values written at the sparse indices.
    Range checked_range(int accessor_index, const std::string& what) const {
        check_accessor_index(accessor_index, what);
        const tinygltf::Accessor& a = model_.accessors[accessor_index];
        const std::string where = fmt::format("{}: accessor {}", what, accessor_index);
        const int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        const int components = component_count(a.type);
        if (component_size <= 0 || components == 0)
            throw_file_error(path_, "{} has an unsupported component type {} or type {}", where, a.componentType, a.type);
        if (a.count == 0) throw_file_error(path_, "{} is empty", where);
        const size_t element_size = size_t(component_size) * components;
        if (!a.sparse.isSparse) {
            const auto [data, stride] = checked_view(a.bufferView, a.byteOffset, a.count, element_size, true, where);
            return Range{data, stride, size_t(component_size), {}};
        }
        Range r{nullptr, element_size, size_t(component_size), {}};
        if (a.bufferView >= 0) {
            const auto [data, stride] = checked_view(a.bufferView, a.byteOffset, a.count, element_size, true, where);
            r.dense.resize(a.count * element_size);
            for (size_t e = 0; e < a.count; ++e) std::memcpy(&r.dense[e * element_size], data + e * stride, element_size);
        } else {
            if (a.count > kMaxDenseBytes / element_size)
                throw_file_error(path_, "{}: {} zero-filled elements of {} bytes are more than rsl reads ({} bytes)",
                                 where, a.count, element_size, kMaxDenseBytes);
            r.dense.assign(a.count * element_size, 0);
        }
        apply_sparse(a, where, element_size, r.dense);
        r.data = r.dense.data();
        return r;
    }

    // Writes a sparse accessor's values at its indices (glTF 2.0 §3.6.2.3).
    void apply_sparse(const tinygltf::Accessor& a, const std::string& where, size_t element_size,
                      std::vector<unsigned char>& dense) const {
        const std::string sparse_where = where + " (sparse)";
        if (a.sparse.count <= 0 || size_t(a.sparse.count) > a.count)
            throw_file_error(path_, "{}: {} sparse elements for an accessor of {}", sparse_where, a.sparse.count, a.count);
        const size_t count = size_t(a.sparse.count);
        const int index_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.sparse.indices.componentType));
        const int index_type = a.sparse.indices.componentType;
        if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throw_file_error(path_, "{}: index component type {} is not an unsigned integer", sparse_where, index_type);
        if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
            throw_file_error(path_, "{}: negative byte offset", sparse_where);
        const unsigned char* indices =
            checked_view(a.sparse.indices.bufferView, size_t(a.sparse.indices.byteOffset), count, size_t(index_size),
                         false, sparse_where + " indices")
                .first;
        const unsigned char* values = checked_view(a.sparse.values.bufferView, size_t(a.sparse.values.byteOffset),
                                                   count, element_size, false, sparse_where + " values")
                                          .first;
        for (size_t k = 0; k < count; ++k) {
            const unsigned char* p = indices + k * size_t(index_size);
            const size_t target = index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? *p
                                  : index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? load<uint16_t>(p)
                                                                                         : load<uint32_t>(p);
            if (target >= a.count)
                throw_file_error(path_, "{}: index {} is {}, out of range for {} elements", sparse_where, k, target, a.count);
            std::memcpy(&dense[target * element_size], values + k * element_size, element_size);
        }
    }

    const tinygltf::Model& model_;
    const std::filesystem::path& path_;
};

}  // namespace rsl::gltf
