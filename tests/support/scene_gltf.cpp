#include "scene_gltf.hpp"
#include "test_support.hpp"

#include <glm/common.hpp>

#include <fstream>
#include <sstream>

namespace jade::test {
namespace {

std::string base64(const std::string& bytes)
{
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v =
            uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
    }
    if (i < bytes.size()) {
        uint32_t v =
            uint32_t(uint8_t(bytes[i])) << 16 | (i + 1 < bytes.size() ? uint32_t(uint8_t(bytes[i + 1])) << 8 : 0u);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

}  // namespace

/// A .gltf with one node per object and the given "materials" array (JSON text).
std::filesystem::path write_gltf(const std::string& name, const std::vector<TestObject>& objects,
                                 const std::string& materials)
{
    std::string buffer;
    std::ostringstream views, accessors, meshes, nodes, roots;
    for (size_t k = 0; k < objects.size(); ++k) {
        const TriangleMesh& m = objects[k].mesh;
        const std::string sep = k ? "," : "";
        const size_t pos_offset = buffer.size();
        buffer.append(reinterpret_cast<const char*>(m.positions.data()), m.positions.size() * 12);
        const size_t idx_offset = buffer.size();
        buffer.append(reinterpret_cast<const char*>(m.indices.data()), m.indices.size() * 4);
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (auto p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        views << sep << R"({"buffer":0,"byteOffset":)" << pos_offset << R"(,"byteLength":)" << m.positions.size() * 12
              << "},"
              << R"({"buffer":0,"byteOffset":)" << idx_offset << R"(,"byteLength":)" << m.indices.size() * 4 << "}";
        accessors << sep << R"({"bufferView":)" << 2 * k << R"(,"componentType":5126,"count":)" << m.positions.size()
                  << R"(,"type":"VEC3","min":[)" << lo.x << "," << lo.y << "," << lo.z << "],\"max\":[" << hi.x << ","
                  << hi.y << "," << hi.z << "]},"
                  << R"({"bufferView":)" << 2 * k + 1 << R"(,"componentType":5125,"count":)" << m.indices.size()
                  << R"(,"type":"SCALAR"})";
        meshes << sep << R"({"primitives":[{"attributes":{"POSITION":)" << 2 * k << R"(},"indices":)" << 2 * k + 1
               << (objects[k].material >= 0 ? ",\"material\":" + std::to_string(objects[k].material) : "") << "}]}";
        nodes << sep << R"({"name":"object)" << k << R"(","mesh":)" << k
              << (objects[k].node_extras.empty() ? "" : ",\"extras\":" + objects[k].node_extras) << "}";
        roots << sep << k;
    }
    std::ostringstream doc;
    doc << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" << roots.str() << "]}],\"nodes\":["
        << nodes.str() << "],\"meshes\":[" << meshes.str() << "],\"accessors\":[" << accessors.str()
        << "],\"bufferViews\":[" << views.str() << "],\"buffers\":[{\"byteLength\":" << buffer.size()
        << ",\"uri\":\"data:application/octet-stream;base64," << base64(buffer) << "\"}],\"materials\":" << materials
        << "}";
    const auto path = test::out("scene/" + name + ".gltf");
    std::ofstream(path) << doc.str();
    return path;
}

}  // namespace jade::test
