// io/load.cpp - jade::load_mesh: reads the file, picks the reader by extension, and turns every
// failure into a jade::Error that names the file.
#include <jade/io.hpp>

#include "io/common.hpp"
#include "io/loaders.hpp"

#include <string>

namespace jade {

namespace {

TriangleMesh read_by_extension(const std::filesystem::path& path, const std::string& name, const ReadOptions& options)
{
    const auto ext = io::lower_extension(path);
    const bool gltf = ext == ".gltf" || ext == ".glb";
    if (!gltf && ext != ".off" && ext != ".ply" && ext != ".obj")
        io::fail(name, "unsupported mesh format '" + ext + "' (supported: .gltf, .glb, .off, .ply, .obj)");
    const std::string bytes = io::read_file(path);
    if (ext == ".off") return io::read_off(name, bytes);
    if (ext == ".ply") return io::read_ply(name, bytes);
    if (ext == ".obj") return io::read_obj(name, bytes);
    return io::read_gltf(path, name, bytes, ext == ".glb", options);
}

}  // namespace

TriangleMesh load_mesh(const std::filesystem::path& path, const ReadOptions& options)
{
    const auto name = io::display_name(path);
    if (options.baked_material) options.baked_material->reset();  // only a baked glTF has one
    return io::naming_file(name, [&] {
        TriangleMesh mesh = read_by_extension(path, name, options);
        io::repair_normals(mesh, options.warnings);
        io::validate_loaded(mesh);
        return mesh;
    });
}

}  // namespace jade
