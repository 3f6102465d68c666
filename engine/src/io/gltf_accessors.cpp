// io/gltf_accessors.cpp - checked access to glTF accessor data; see gltf_accessors.hpp.
#include "io/gltf_accessors.hpp"

#include "io/common.hpp"

#include <algorithm>
#include <bit>

namespace jade::io {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian and read in place");

namespace {

const char* type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

const char* component_name(int component)
{
    switch (component) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown";
    }
}

size_t component_size(int component)
{
    switch (component) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    default: return 4;
    }
}

}  // namespace

uint32_t AccessorView::index(size_t i) const
{
    if (!data) return 0;
    const unsigned char* p = data + i * stride;
    if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *p;
    if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

AccessorView AccessorReader::view(const std::string& where, int index, const AccessorSpec& spec) const
{
    const std::string subject = where + "accessor " + std::to_string(index) + " (" + spec.role + "): ";
    if (index < 0 || size_t(index) >= model_.accessors.size()) fail(file_, subject + "does not exist");
    const auto& a = model_.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(file_, subject + "sparse accessors are not supported");
    if (a.type != spec.type)
        fail(file_, subject + "type is " + type_name(a.type) + ", expected " + type_name(spec.type));
    if (std::find(spec.components.begin(), spec.components.end(), a.componentType) == spec.components.end())
        fail(file_, subject + "component type " + component_name(a.componentType) + " (" +
                        std::to_string(a.componentType) + ") is not supported here");
    AccessorView v;
    v.count = a.count;
    v.component = a.componentType;
    const size_t element = component_size(a.componentType) * size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    if (a.bufferView < 0) return v;  // the spec says: all zeros
    const auto range = buffer_view(subject, a.bufferView);
    v.stride = range.stride ? range.stride : element;
    if (v.stride < element)
        fail(file_, subject + "byteStride " + std::to_string(v.stride) + " is smaller than an element (" +
                        std::to_string(element) + " bytes)");
    check_fits(subject, a, element, v.stride, range.length, a.bufferView);
    v.data = range.data + a.byteOffset;
    return v;
}

AccessorReader::ViewRange AccessorReader::buffer_view(const std::string& subject, int index) const
{
    const std::string view = "bufferView " + std::to_string(index);
    if (size_t(index) >= model_.bufferViews.size()) fail(file_, subject + view + " does not exist");
    const auto& bv = model_.bufferViews[size_t(index)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        fail(file_, subject + view + ": buffer " + std::to_string(bv.buffer) + " does not exist");
    const auto& data = model_.buffers[size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        fail(file_, subject + view + " (bytes " + std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
                        ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" +
                        std::to_string(data.size()) + " bytes)");
    return {data.data() + bv.byteOffset, bv.byteLength, bv.byteStride};
}

void AccessorReader::check_fits(const std::string& subject, const tinygltf::Accessor& a, size_t element, size_t stride,
                size_t length, int view) const
{
    if (a.count == 0) return;
    // Overflow-safe form of byteOffset + (count - 1) * stride + element <= length.
    const bool fits = a.byteOffset <= length && element <= length - a.byteOffset &&
                      a.count - 1 <= (length - a.byteOffset - element) / stride;
    if (!fits)
        fail(file_, subject + std::to_string(a.count) + " elements of " + std::to_string(element) + " bytes (stride " +
                        std::to_string(stride) + ") from byteOffset " + std::to_string(a.byteOffset) +
                        " do not fit in bufferView " + std::to_string(view) + " (" + std::to_string(length) +
                        " bytes)");
}

}  // namespace jade::io
