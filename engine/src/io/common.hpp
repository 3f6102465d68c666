// io/common.hpp - helpers shared by the mesh and image readers and writers (private to jade_io).
//
// Every reader works on the whole file in memory: the file is read once with a size check, and
// each header count is checked against the bytes that follow it before anything is allocated
// for it, so a corrupt or hostile header fails fast instead of allocating gigabytes.
#pragma once

#include "mesh/validate.hpp"

#include <jade/error.hpp>
#include <jade/mesh.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <new>
#include <stdexcept>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace jade::io {

/// Largest file any reader accepts. Bigger meshes do not fit the 32-bit indices of the bake
/// anyway, and tinygltf takes lengths as `unsigned int`.
inline constexpr uint64_t kMaxFileBytes = uint64_t(2) << 30;

/// Largest vertex count a loaded mesh may have: indices are uint32 and PreparedMesh::kUnused
/// (0xffffffff) is reserved.
inline constexpr uint64_t kMaxVertices = 0xfffffffeu;

/// Largest triangle count a loaded mesh may have (triangle ids are 32-bit in the bake, too).
inline constexpr uint64_t kMaxTriangles = 0xfffffffeu;

/// The name used in messages and TriangleMesh::name: the file name without its folder.
std::string display_name(const std::filesystem::path& path);

/// Throws jade::Error("<file>: <what>").
[[noreturn]] void fail(std::string_view file, std::string_view what);

/// Runs `read` (a whole-file reader) and turns what is not a jade::Error - out of memory, the
/// third-party parsers' own exception types (nlohmann::json, std::) - into one naming `file`.
template <class Read> auto naming_file(std::string_view file, Read&& read) -> decltype(read())
{
    try {
        return read();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        fail(file, "out of memory while loading");
    } catch (const std::exception& e) {
        fail(file, std::string("cannot load: ") + e.what());
    }
}

/// Reads a whole regular file, refusing files larger than `max_bytes` before reading them.
std::string read_file(const std::filesystem::path& path, uint64_t max_bytes = kMaxFileBytes);

/// Rejects a header count before anything is allocated for it: `count` elements of at least
/// `min_bytes_each` bytes each must fit in the `bytes_left` bytes that follow the header.
/// `what` names the element in the plural ("vertices", "faces").
void check_count(std::string_view file, std::string_view what, uint64_t count, uint64_t min_bytes_each,
                 uint64_t bytes_left);

/// Appends the fan triangulation (p0, p[i], p[i+1]) of a polygon with at least 3 corners. The
/// fan keeps the polygon's winding; it is exact for convex polygons, which is what OFF, PLY and
/// OBJ files hold in practice.
void append_fan(std::span<const uint32_t> polygon, std::vector<uint32_t>& indices);

/// The first vertex whose normal is not finite or is zero, and which ("not finite", "zero");
/// vertex -1 when every normal is good or there are none.
struct BadNormal {
    long long vertex = -1;
    const char* what = "";
};
BadNormal first_bad_normal(const TriangleMesh& mesh);

/// Replaces every normal that is not finite or zero by the area-weighted normal of the
/// triangles around its vertex (or +z where those have no area), so that none is copied into an
/// output; says so in `warnings` (naming the file and the first such vertex) when given.
void repair_normals(TriangleMesh& mesh, std::vector<std::string>* warnings);

/// Checks what every reader must guarantee: jade::validate_mesh, and at least one triangle.
void validate_loaded(const TriangleMesh& mesh);

/// File content quoted in a message: bytes outside printable ASCII become '?' and text longer
/// than `max` is cut with "...", so a binary file read as text cannot garble the message.
std::string printable(std::string_view text, size_t max = 32);

/// A third-party parser's message as one line, with overlong words (tinygltf quotes whole data
/// URIs) shortened.
std::string one_line(const std::string& message);

/// A file created for this process alone: its path and an open, writable descriptor.
struct TemporaryFile {
    std::filesystem::path path;
    int fd = -1;
};

/// Creates "<path>.tmp-<pid>-<12 random hex digits>" beside `path`, exclusively (O_CREAT |
/// O_EXCL | O_NOFOLLOW: a file or link planted under the name is never opened, another name is
/// tried), mode 0666 less the umask. Throws jade::Error naming `path`.
TemporaryFile create_temporary_beside(const std::filesystem::path& path);

/// Writes a file atomically, the one way every writer of Jade does: `write` fills the temporary
/// file of create_temporary_beside (by its descriptor, or by its name, which only this process
/// knows), which gets the mode (and, where allowed, the owner) of the file it replaces, is synced
/// to disk (fsync), renamed to `path`, and the folder synced, so that a crash at any moment
/// leaves the old file or the complete new one. A link at `path` is replaced, not followed. On
/// any failure the temporary file is removed and the error is rethrown as jade::Error.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp, int fd)>& write);
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

/// Lower-case extension with its dot (".glb"), for dispatching on the file type.
std::string lower_extension(const std::filesystem::path& path);

}  // namespace jade::io
