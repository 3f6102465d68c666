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
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
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
    if (a.type != spec.type)
        fail(file_, subject + "type is " + type_name(a.type) + ", expected " + type_name(spec.type));
    if (std::find(spec.components.begin(), spec.components.end(), a.componentType) == spec.components.end())
        fail(file_, subject + "component type " + component_name(a.componentType) + " (" +
                        std::to_string(a.componentType) + ") is not supported here");
    AccessorView v;
    v.count = a.count;
    v.component = a.componentType;
    const size_t element = component_size(a.componentType) * size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    if (a.bufferView >= 0) {  // without one, the spec says: all zeros
        const auto range = buffer_view(subject, a.bufferView);
        v.stride = range.stride ? range.stride : element;
        if (v.stride < element)
            fail(file_, subject + "byteStride " + std::to_string(v.stride) + " is smaller than an element (" +
                            std::to_string(element) + " bytes)");
        check_fits(subject, a.count, a.byteOffset, element, v.stride, range.length,
                   "bufferView " + std::to_string(a.bufferView));
        v.data = range.data + a.byteOffset;
    }
    if (a.sparse.isSparse) expand_sparse(subject, a, element, v);
    return v;
}

void AccessorReader::expand_sparse(const std::string& subject, const tinygltf::Accessor& a, size_t element,
                                   AccessorView& v) const
{
    const std::string sparse = subject + "sparse ";
    // The dense copy is allocated here, so its size is bounded like a file's.
    if (a.count > kMaxVertices || a.count * element > kMaxFileBytes)
        fail(file_, sparse + "accessor of " + std::to_string(a.count) + " elements is too large to expand");
    const size_t n = size_t(a.sparse.count);
    if (a.sparse.count < 1 || n > a.count)
        fail(file_, sparse + "count " + std::to_string(a.sparse.count) + " is not in 1.." + std::to_string(a.count));
    const int ic = a.sparse.indices.componentType;
    if (ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(file_, sparse + "indices component type " + component_name(ic) + " is not an unsigned integer type");
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
        fail(file_, sparse + "byteOffset is negative");
    const size_t isize = component_size(ic);
    const auto indices = buffer_view(sparse + "indices: ", a.sparse.indices.bufferView);
    check_fits(sparse + "indices: ", n, size_t(a.sparse.indices.byteOffset), isize, isize, indices.length,
               "bufferView " + std::to_string(a.sparse.indices.bufferView));
    const auto values = buffer_view(sparse + "values: ", a.sparse.values.bufferView);
    check_fits(sparse + "values: ", n, size_t(a.sparse.values.byteOffset), element, element, values.length,
               "bufferView " + std::to_string(a.sparse.values.bufferView));

    auto dense = std::make_shared<std::vector<unsigned char>>(a.count * element, 0);
    for (size_t i = 0; i < a.count; ++i) v.bytes(i, dense->data() + i * element, element);
    const AccessorView index_view{indices.data + a.sparse.indices.byteOffset, isize, n, ic, nullptr};
    const unsigned char* value = values.data + a.sparse.values.byteOffset;
    for (size_t k = 0; k < n; ++k) {
        const uint32_t i = index_view.index(k);
        if (i >= a.count)
            fail(file_, sparse + "index " + std::to_string(i) + " (entry " + std::to_string(k) +
                            ") is out of range for " + std::to_string(a.count) + " elements");
        if (k > 0 && i <= index_view.index(k - 1))
            fail(file_, sparse + "indices are not strictly increasing at entry " + std::to_string(k));
        std::memcpy(dense->data() + size_t(i) * element, value + k * element, element);
    }
    v.data = dense->data();
    v.stride = element;
    v.dense = std::move(dense);
}

AccessorReader::ViewRange AccessorReader::buffer_view(const std::string& subject, int index) const
{
    const std::string view = "bufferView " + std::to_string(index);
    if (index < 0 || size_t(index) >= model_.bufferViews.size()) fail(file_, subject + view + " does not exist");
    const auto& bv = model_.bufferViews[size_t(index)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        fail(file_, subject + view + ": buffer " + std::to_string(bv.buffer) + " does not exist");
    const auto& data = model_.buffers[size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        fail(file_, subject + view + " (bytes " + std::to_string(bv.byteOffset) + " + " +
                        std::to_string(bv.byteLength) + ") runs past the end of buffer " + std::to_string(bv.buffer) +
                        " (" + std::to_string(data.size()) + " bytes)");
    return {data.data() + bv.byteOffset, bv.byteLength, bv.byteStride};
}

void AccessorReader::check_fits(const std::string& subject, size_t count, size_t offset, size_t element, size_t stride,
                                size_t length, const std::string& view) const
{
    if (count == 0) return;
    // Overflow-safe form of offset + (count - 1) * stride + element <= length.
    const bool fits =
        offset <= length && element <= length - offset && count - 1 <= (length - offset - element) / stride;
    if (!fits)
        fail(file_, subject + std::to_string(count) + " elements of " + std::to_string(element) + " bytes (stride " +
                        std::to_string(stride) + ") from byteOffset " + std::to_string(offset) + " do not fit in " +
                        view + " (" + std::to_string(length) + " bytes)");
}

}  // namespace jade::io
