// io/obj.cpp - Wavefront OBJ reader, on top of tinyobjloader.
//
// Positions become the render vertices (one per `v` line) and faces index them directly; `vn`
// normals are used when every face corner has one (the first normal seen for a position wins).
// Texture coordinates, materials, lines and points are ignored.
#include "io/loaders.hpp"
#include "io/common.hpp"

#include <tiny_obj_loader.h>

namespace jade::io {

namespace {

void copy_positions(const std::string& name, const tinyobj::attrib_t& attrib, TriangleMesh& mesh)
{
    const size_t count = attrib.vertices.size() / 3;
    if (count > kMaxVertices) fail(name, std::to_string(count) + " vertices, more than 32-bit indices can address");
    mesh.positions.resize(count);
    for (size_t v = 0; v < count; ++v)
        mesh.positions[v] = {attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]};
}

/// Reads the faces of one shape, checking each index before it is used.
void add_shape(const std::string& name, const tinyobj::shape_t& shape, size_t normal_count, TriangleMesh& mesh,
               bool& all_normals)
{
    const auto& corners = shape.mesh.indices;
    const size_t vertex_count = mesh.positions.size();
    const std::string where = shape.name.empty() ? std::string("face ") : "shape '" + printable(shape.name) + "' face ";
    std::vector<uint32_t> polygon;
    size_t next = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
        const size_t n = shape.mesh.num_face_vertices[f];
        // tinyobjloader stores face sizes as unsigned char: a larger polygon leaves the sizes
        // out of step with the corners, which this catches.
        if (n < 3 || next + n > corners.size())
            fail(name, where + std::to_string(f) + " has " + std::to_string(n) + " vertices (3 to 255 supported)");
        polygon.clear();
        for (size_t k = 0; k < n; ++k) {
            const auto& c = corners[next + k];
            // tinyobjloader has already resolved relative (negative) indices: report the
            // 1-based number the file would need, or that the reference points before vertex 1.
            if (c.vertex_index < 0)
                fail(name, where + std::to_string(f) + ": a relative vertex index refers to a vertex before the first");
            if (size_t(c.vertex_index) >= vertex_count)
                fail(name, where + std::to_string(f) + ": vertex index " + std::to_string(int64_t(c.vertex_index) + 1) +
                               " out of range for " + std::to_string(vertex_count) + " vertices");
            polygon.push_back(static_cast<uint32_t>(c.vertex_index));
            if (c.normal_index < 0 || size_t(c.normal_index) >= normal_count) all_normals = false;
        }
        append_fan(polygon, mesh.indices);
        next += n;
    }
    if (next != corners.size())
        fail(name, where + "list does not match its corners (a polygon with more than 255 vertices?)");
}

/// Assigns each position the first `vn` normal a face corner gives it.
void add_normals(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes, TriangleMesh& mesh)
{
    std::vector<bool> set(mesh.positions.size(), false);
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (const auto& shape : shapes) {
        for (const auto& c : shape.mesh.indices) {
            if (set[size_t(c.vertex_index)]) continue;
            const size_t n = size_t(c.normal_index);
            mesh.normals[size_t(c.vertex_index)] = {attrib.normals[3 * n], attrib.normals[3 * n + 1],
                                                    attrib.normals[3 * n + 2]};
            set[size_t(c.vertex_index)] = true;
        }
    }
}

/// tinyobjloader's "vw" extension (skin weights) converts each joint id to int unchecked, which is
/// undefined behaviour for ids like 1e39 (found by fuzz_obj). Jade reads no skin weights, so such
/// lines are turned into comments (same length, same line numbers) before parsing.
std::string without_skin_weights(const std::string& bytes)
{
    std::string out;
    bool line_start = true;
    for (size_t i = 0; i < bytes.size(); ++i) {
        const char c = bytes[i];
        if (c == '\n' || c == '\r') {
            line_start = true;
        } else if (line_start && c != ' ' && c != '\t') {
            line_start = false;
            if (c == 'v' && i + 2 < bytes.size() && bytes[i + 1] == 'w' &&
                (bytes[i + 2] == ' ' || bytes[i + 2] == '\t')) {
                if (out.empty()) out = bytes;  // copied only when the file has such a line
                out[i] = '#';
            }
        }
    }
    return out;
}

}  // namespace

TriangleMesh read_obj(const std::string& name, const std::string& bytes)
{
    tinyobj::ObjReaderConfig config;
    // tinyobjloader's triangulation reads positions through indices it has not checked, so
    // faces are read as polygons and fan-triangulated here after checking their indices.
    config.triangulate = false;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    const std::string cleaned = without_skin_weights(bytes);
    if (!reader.ParseFromString(cleaned.empty() ? bytes : cleaned, std::string(), config))
        fail(name, "tinyobjloader: " + one_line(reader.Error().empty() ? "parse failed" : reader.Error()));

    TriangleMesh mesh;
    mesh.name = name;
    copy_positions(name, reader.GetAttrib(), mesh);
    bool all_normals = true;
    const size_t normal_count = reader.GetAttrib().normals.size() / 3;
    for (const auto& shape : reader.GetShapes()) add_shape(name, shape, normal_count, mesh, all_normals);
    if (all_normals && !mesh.indices.empty()) add_normals(reader.GetAttrib(), reader.GetShapes(), mesh);
    return mesh;
}

}  // namespace jade::io
