// io/gltf_model.hpp - parsing a glTF file into a tinygltf::Model (private to jade_io).
#pragma once

#include <jade/io.hpp>
#include <jade/mesh.hpp>

#include <tiny_gltf.h>

#include <glm/mat4x4.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace jade::io {

/// Parses a .gltf or .glb held in memory. The GLB container is checked first (tinygltf 2.7 lets
/// a BIN chunk run 8 bytes past the end of the file); external buffers are read only from the
/// folder of `path` and below it (a URI outside it is an error naming the buffer or image),
/// within the file size limit; images are never decoded.
/// A URI whose target's real path (links resolved) leaves the folder is refused too, unless
/// `options.allow_outside_links`.
/// `images`, when given, receives the bytes of every image tinygltf read (external files and
/// data URIs; empty for an image it could not read), indexed like model.images. `files`, when
/// given, receives the real path of every external file read.
tinygltf::Model parse_gltf(const std::filesystem::path& path, const std::string& name, const std::string& bytes,
                           bool binary, const ReadOptions& options,
                           std::vector<std::vector<unsigned char>>* images = nullptr,
                           std::vector<std::filesystem::path>* files = nullptr);

/// Rejects every required extension except those that only change materials or textures,
/// naming it (compressed geometry, KHR_mesh_quantization, ...).
void check_required_extensions(const std::string& name, const tinygltf::Model& model);

/// A node of the default scene (or scene 0, or without scenes every root node) with a mesh, and
/// its world matrix; in depth-first order of the node trees, the order read_gltf merges them.
struct MeshInstance {
    int mesh;
    glm::dmat4 world;
    int node;
};
std::vector<MeshInstance> scene_mesh_instances(const std::string& name, const tinygltf::Model& model);

/// TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN (or the default mode).
bool is_triangle_mode(int mode);

/// Primitive `primitive` of mesh `mesh` read as read_gltf reads it, transformed by `world`
/// (triangles of strips and fans listed, winding kept; one position per stored vertex, in order).
TriangleMesh read_gltf_primitive(const std::string& name, const tinygltf::Model& model, int mesh, size_t primitive,
                                 const glm::dmat4& world);

/// One triangle primitive of one mesh instance of the default scene, in world space, read as
/// read_gltf reads meshes (io/gltf.cpp); io/scene_gltf.cpp makes a scene object of each.
struct GltfPrimitive {
    TriangleMesh mesh;
    int node, mesh_index, primitive, material;  ///< material: -1 when none
};
std::vector<GltfPrimitive> read_gltf_primitives(const std::string& name, const tinygltf::Model& model);

}  // namespace jade::io
