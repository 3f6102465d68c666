// io/gltf_save.cpp - jade::save_baked_gltf: the mesh with its baked attributes as glTF 2.0.
//
// The document is written with nlohmann::json rather than tinygltf's serializer so that the
// caller's `extras` JSON is stored exactly as given (tinygltf's Value drops nulls and narrows
// integers). One buffer holds, in order: POSITION, NORMAL, _AO, _TM, _THICKNESS,
// _SCATTERING_NORMAL, _NORMAL_SPREAD (all float, so every view stays 4-byte aligned) and uint32
// indices. .glb puts it in the BIN chunk, .gltf in a base64 data URI. The one material carries
// the bake's Jade material (JADE_materials_translucency, io/gltf_translucency.hpp).
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include "io/common.hpp"
#include "io/gltf_container.hpp"
#include "io/gltf_translucency.hpp"

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>

namespace jade {

namespace {

using json = nlohmann::ordered_json;  // keys in the order written

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

void check_input(const std::string& name, const TriangleMesh& mesh, const BakedAttributes& baked)
{
    try {
        validate_mesh(mesh);
    } catch (const Error& e) {
        io::fail(name, std::string("cannot save: ") + e.what());  // the message names the mesh
    }
    if (mesh.indices.empty()) io::fail(name, "cannot save a mesh without triangles");
    const size_t n = mesh.positions.size();
    auto check_size = [&](size_t size, const char* what) {
        if (size != 0 && size != n)
            io::fail(name, std::to_string(size) + " " + what + " values for " + std::to_string(n) + " vertices");
    };
    check_size(baked.ao.size(), "_AO");
    check_size(baked.tm.size(), "_TM");
    check_size(baked.thickness.size(), "_THICKNESS");
    check_size(baked.scattering_normal.size(), "_SCATTERING_NORMAL");
    check_size(baked.normal_spread.size(), "_NORMAL_SPREAD");
    // Never a NaN or an Inf in a file: other tools take them for values (a NaN t_m shades black or
    // poisons a filter). Named by the first vertex at fault.
    const auto finite3 = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    for (size_t v = 0; v < n; ++v) {
        const char* bad = !baked.ao.empty() && !std::isfinite(baked.ao[v])                 ? "_AO"
                          : !baked.tm.empty() && !finite3(baked.tm[v])                     ? "_TM"
                          : !baked.thickness.empty() && !std::isfinite(baked.thickness[v]) ? "_THICKNESS"
                          : !baked.scattering_normal.empty() && !finite3(baked.scattering_normal[v])
                              ? "_SCATTERING_NORMAL"
                          : !baked.normal_spread.empty() && !finite3(baked.normal_spread[v]) ? "_NORMAL_SPREAD"
                          : !mesh.normals.empty() && !finite3(mesh.normals[v])               ? "NORMAL"
                          : !mesh.normals.empty() && mesh.normals[v] == glm::vec3(0.0f)      ? "NORMAL*"
                                                                                             : nullptr;
        if (!bad) continue;
        const std::string what = bad[6] == '*'
                                     ? "NORMAL of vertex " + std::to_string(v) + " is zero"
                                     : bad + std::string(" of vertex ") + std::to_string(v) + " is not finite";
        io::fail(name, "cannot save: " + what + " (" + mesh.name + "); nothing was written");
    }
}

json parse_extras(const std::string& name, const std::string& text)
{
    if (text.empty()) return json();
    json extras;
    try {
        extras = json::parse(text);
    } catch (const json::exception& e) {
        io::fail(name, std::string("extras_json is not valid JSON: ") + e.what());
    }
    if (!extras.is_object()) io::fail(name, "extras_json must be a JSON object");
    return extras;
}

/// Builds the buffer, its views and accessors as attributes are added.
class Document {
public:
    /// Appends `count` elements of `components` floats; returns the accessor index.
    int add_floats(const float* data, size_t count, int components)
    {
        static const char* const kTypes[] = {"", "SCALAR", "", "VEC3"};
        json accessor = {{"componentType", kFloat}, {"count", count}, {"type", kTypes[components]}};
        return add(data, count * size_t(components) * sizeof(float), kArrayBuffer, std::move(accessor));
    }

    int add_positions(const std::vector<glm::vec3>& p)
    {
        glm::vec3 lo = p[0], hi = p[0];
        for (const auto& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
        const int index = add_floats(&p[0].x, p.size(), 3);
        // Accessor bounds are required for POSITION; doubles print each float exactly.
        accessors_[size_t(index)]["min"] = {double(lo.x), double(lo.y), double(lo.z)};
        accessors_[size_t(index)]["max"] = {double(hi.x), double(hi.y), double(hi.z)};
        return index;
    }

    int add_indices(const std::vector<uint32_t>& indices)
    {
        json accessor = {{"componentType", kUnsignedInt}, {"count", indices.size()}, {"type", "SCALAR"}};
        return add(indices.data(), indices.size() * sizeof(uint32_t), kElementArrayBuffer, std::move(accessor));
    }

    const std::vector<unsigned char>& buffer() const { return buffer_; }
    json views() const { return views_; }
    json accessors() const { return accessors_; }

private:
    int add(const void* data, size_t bytes, int target, json accessor)
    {
        const size_t offset = buffer_.size();
        buffer_.resize(offset + bytes);
        std::memcpy(buffer_.data() + offset, data, bytes);
        views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
        accessor["bufferView"] = views_.size() - 1;
        accessors_.push_back(std::move(accessor));
        return int(accessors_.size() - 1);
    }

    std::vector<unsigned char> buffer_;
    json views_ = json::array();
    json accessors_ = json::array();
};

json build_json(const std::string& name, const TriangleMesh& mesh, const BakedAttributes& baked, json extras,
                Document& doc)
{
    json attributes;
    attributes["POSITION"] = doc.add_positions(mesh.positions);
    if (!mesh.normals.empty()) attributes["NORMAL"] = doc.add_floats(&mesh.normals[0].x, mesh.normals.size(), 3);
    if (!baked.ao.empty()) attributes["_AO"] = doc.add_floats(baked.ao.data(), baked.ao.size(), 1);
    if (!baked.tm.empty()) attributes["_TM"] = doc.add_floats(&baked.tm[0].x, baked.tm.size(), 3);
    if (!baked.thickness.empty())
        attributes["_THICKNESS"] = doc.add_floats(baked.thickness.data(), baked.thickness.size(), 1);
    if (!baked.scattering_normal.empty())
        attributes["_SCATTERING_NORMAL"] =
            doc.add_floats(&baked.scattering_normal[0].x, baked.scattering_normal.size(), 3);
    if (!baked.normal_spread.empty())
        attributes["_NORMAL_SPREAD"] = doc.add_floats(&baked.normal_spread[0].x, baked.normal_spread.size(), 3);
    const int indices = doc.add_indices(mesh.indices);

    json asset = {{"version", "2.0"}, {"generator", "Jade"}};
    if (!extras.is_null()) asset["extras"] = std::move(extras);
    json primitive = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
    json document = {
        {"asset", asset},
        {"scene", 0},
        {"scenes", json::array({{{"nodes", {0}}}})},
        {"nodes", json::array({{{"mesh", 0}, {"name", mesh.name}}})},
        {"meshes", json::array({{{"name", mesh.name}, {"primitives", json::array({primitive})}}})},
        {"bufferViews", doc.views()},
        {"accessors", doc.accessors()},
    };
    if (baked.material && !baked.material->opaque) {
        // A vendor extension other viewers ignore: used, not required.
        document["meshes"][0]["primitives"][0]["material"] = 0;
        document["materials"] = json::array(
            {{{"name", baked.material->name},
              {"extensions", {{io::kTranslucencyExtension, io::translucency_extension(name, *baked.material)}}}}});
        document["extensionsUsed"] = json::array({io::kTranslucencyExtension});
    }
    return document;
}

std::string dump(const json& j)
{
    // Mesh names come from file names: replace invalid UTF-8 rather than throw.
    return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string to_glb(const std::string& name, json document, const std::vector<unsigned char>& buffer)
{
    document["buffers"] = json::array({{{"byteLength", buffer.size()}}});
    return io::glb_container(name, dump(document), buffer);
}

std::string to_gltf(json document, const std::vector<unsigned char>& buffer)
{
    document["buffers"] = json::array(
        {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + io::base64(buffer)}}});
    return dump(document);
}

}  // namespace

void save_baked_gltf(const std::filesystem::path& path, const TriangleMesh& mesh, const BakedAttributes& baked)
{
    const auto name = io::display_name(path);
    const auto ext = io::lower_extension(path);
    if (ext != ".glb" && ext != ".gltf")
        io::fail(name, "unsupported glTF extension '" + ext + "' (supported: .glb, .gltf)");
    check_input(name, mesh, baked);
    Document doc;
    const json document = build_json(name, mesh, baked, parse_extras(name, baked.extras_json), doc);
    const std::string bytes = ext == ".glb" ? to_glb(name, document, doc.buffer()) : to_gltf(document, doc.buffer());
    dev::write_file_atomically(path, bytes);
}

}  // namespace jade
