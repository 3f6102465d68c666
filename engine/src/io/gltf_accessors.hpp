// io/gltf_accessors.hpp - checked access to glTF accessor data (private to jade_io).
//
// Every accessor is checked before it is read: it exists, has the expected type and component
// type, and each of its elements lies inside its bufferView, which lies inside its buffer. Reads
// are then plain memcpy's at offset + i * stride. A sparse accessor is expanded once into a dense
// copy that the view owns (its indices checked: in range and strictly increasing).
#pragma once

#include <tiny_gltf.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace jade::io {

/// A checked view of an accessor's elements (little-endian data, read in place).
struct AccessorView {
    const unsigned char* data = nullptr;  ///< nullptr: no bufferView, every element is zero
    size_t stride = 0;
    size_t count = 0;
    int component = 0;
    std::shared_ptr<const std::vector<unsigned char>> dense;  ///< a sparse accessor's expanded data

    /// Element i's bytes (`size` of them: component size × components).
    void bytes(size_t i, void* out, size_t size) const
    {
        if (data)
            std::memcpy(out, data + i * stride, size);
        else
            std::memset(out, 0, size);
    }

    glm::vec3 vec3(size_t i) const
    {
        glm::vec3 v(0.0f);
        if (data) std::memcpy(&v, data + i * stride, sizeof v);
        return v;
    }
    float scalar(size_t i) const
    {
        float v = 0.0f;
        if (data) std::memcpy(&v, data + i * stride, sizeof v);
        return v;
    }
    /// An UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT index.
    uint32_t index(size_t i) const;
};

/// What an attribute or index accessor must be.
struct AccessorSpec {
    const char* role;  ///< "POSITION", "indices", ... for messages
    int type;          ///< TINYGLTF_TYPE_*
    std::initializer_list<int> components;
};

class AccessorReader {
public:
    AccessorReader(const std::string& file, const tinygltf::Model& model) : file_(file), model_(model) {}

    /// Checks accessor `index` against `spec` and its byte ranges. `where` prefixes messages
    /// ("mesh 0 primitive 1: "), which then read "... accessor 3 (indices): ...".
    AccessorView view(const std::string& where, int index, const AccessorSpec& spec) const;

private:
    struct ViewRange {
        const unsigned char* data;
        size_t length, stride;
    };
    ViewRange buffer_view(const std::string& subject, int index) const;
    void check_fits(const std::string& subject, size_t count, size_t offset, size_t element, size_t stride,
                    size_t length, const std::string& view) const;
    void expand_sparse(const std::string& subject, const tinygltf::Accessor& a, size_t element, AccessorView& v) const;

    const std::string& file_;
    const tinygltf::Model& model_;
};

}  // namespace jade::io
