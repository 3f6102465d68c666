// io/loaders.hpp - the per-format mesh readers behind jade::load_mesh (private to jade_io).
//
// Each reader gets the whole file in memory and the name to use in messages, and throws
// jade::Error naming that file and the offending element. load_mesh (io/load.cpp) then runs the
// checks common to all formats (io::validate_loaded).
#pragma once

#include <jade/io.hpp>
#include <jade/mesh.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace jade::io {

TriangleMesh read_off(const std::string& name, std::string_view bytes);
TriangleMesh read_ply(const std::string& name, std::string_view bytes);
TriangleMesh read_obj(const std::string& name, const std::string& bytes);
/// `path` locates external buffers (relative URIs are resolved in its folder, and only there).
TriangleMesh read_gltf(const std::filesystem::path& path, const std::string& name, const std::string& bytes,
                       bool binary, const ReadOptions& options);

}  // namespace jade::io
