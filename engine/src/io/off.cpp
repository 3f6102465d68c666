// io/off.cpp - OFF reader (Geomview Object File Format, ASCII).
//
// Accepted: an optional header keyword "[ST][C][N]OFF" (colours and texture coordinates are
// skipped, N-normals are read), '#' comments anywhere, counts on the header line or the next
// one, polygons of any size (fan-triangulated). Extra values at the end of a vertex or face line
// (colours) are skipped. Rejected with an error: binary OFF, 4D/nD OFF, faces with fewer than
// 3 vertices, indices out of range, truncated files.
#include "io/loaders.hpp"
#include "io/text_reader.hpp"

#include <glm/vec3.hpp>

namespace jade::io {

namespace {

struct OffHeader {
    bool normals = false;  ///< "NOFF": each vertex line carries x y z nx ny nz
    uint64_t vertices = 0, faces = 0;
};

// Shortest possible text of one element, to check header counts against the file size:
// "0 0 0\n" for a vertex and "3 0 0 0\n" for a face, less the last separator.
constexpr uint64_t kMinVertexBytes = 5;
constexpr uint64_t kMinFaceBytes = 7;

void parse_keyword(TextReader& in, OffHeader& header)
{
    auto keyword = in.peek();
    if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") return;  // headerless
    in.next();
    auto prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.starts_with("ST")) prefix.remove_prefix(2);
    if (prefix.starts_with("C")) prefix.remove_prefix(1);
    if (prefix.starts_with("N")) {
        header.normals = true;
        prefix.remove_prefix(1);
    }
    if (prefix.starts_with("4") || prefix.starts_with("n"))
        in.fail("'" + printable(keyword) + "': 4D and n-dimensional OFF files are not supported");
    if (!prefix.empty()) in.fail("unknown header keyword '" + printable(keyword) + "'");
    if (in.peek() == "BINARY") in.fail("binary OFF files are not supported (only ASCII)");
}

OffHeader parse_header(TextReader& in, const std::string& name)
{
    OffHeader header;
    parse_keyword(in, header);
    header.vertices = in.count("vertex count");
    header.faces = in.count("face count");
    in.skip_line();  // the edge count, unused and sometimes missing
    check_count(name, "vertices", header.vertices, kMinVertexBytes, in.bytes_left());
    check_count(name, "faces", header.faces, kMinFaceBytes, in.bytes_left());
    return header;
}

void read_vertices(TextReader& in, const OffHeader& header, TriangleMesh& mesh)
{
    mesh.positions.resize(header.vertices);
    if (header.normals) mesh.normals.resize(header.vertices);
    for (uint64_t v = 0; v < header.vertices; ++v) {
        for (int c = 0; c < 3; ++c) mesh.positions[v][c] = static_cast<float>(in.real({"coordinate of vertex", v}));
        if (header.normals)
            for (int c = 0; c < 3; ++c) mesh.normals[v][c] = static_cast<float>(in.real({"normal of vertex", v}));
        in.skip_line();  // colours, texture coordinates
    }
}

void read_faces(TextReader& in, const OffHeader& header, TriangleMesh& mesh)
{
    mesh.indices.reserve(header.faces * 3);
    std::vector<uint32_t> polygon;
    for (uint64_t f = 0; f < header.faces; ++f) {
        const uint64_t corners = in.count({"vertex count of face", f});
        if (corners < 3)
            in.fail("face " + std::to_string(f) + " has " + std::to_string(corners) + " vertices (at least 3 needed)");
        polygon.clear();
        for (uint64_t k = 0; k < corners; ++k) {
            const uint64_t index = in.count({"vertex index of face", f});
            if (index >= header.vertices)
                in.fail("face " + std::to_string(f) + ": vertex index " + std::to_string(index) + " out of range for " +
                        std::to_string(header.vertices) + " vertices");
            polygon.push_back(static_cast<uint32_t>(index));
        }
        append_fan(polygon, mesh.indices);
        in.skip_line();  // face colour
    }
}

}  // namespace

TriangleMesh read_off(const std::string& name, std::string_view bytes)
{
    TextReader in(name, bytes);
    if (in.at_end()) fail(name, "file is empty");
    const auto header = parse_header(in, name);
    TriangleMesh mesh;
    mesh.name = name;
    read_vertices(in, header, mesh);
    read_faces(in, header, mesh);
    return mesh;
}

}  // namespace jade::io
