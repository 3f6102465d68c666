// jade/io.hpp - file formats. Part of the separate target jade::io (links tinygltf,
// tinyobjloader, OpenImageIO); the core library jade::jade reads and writes no files.
#pragma once

#include <jade/deform.hpp>
#include <jade/mesh.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace jade {

/// Loads a triangle mesh, choosing the reader by extension (case-insensitive):
///   .gltf / .glb  glTF 2.0: every triangle primitive of the default scene (or scene 0), node
///                 transforms applied, indexed or not; reads `_AO`/`_TM`/`_THICKNESS` if present.
///   .off          OFF (polygons are fan-triangulated)
///   .ply          PLY, ASCII or binary little-endian (faces fan-triangulated)
///   .obj          Wavefront OBJ (via tinyobjloader)
/// Throws jade::Error naming the file, the element and what is wrong; never returns a partly
/// read mesh. Header counts are checked against the file size before anything is allocated.
TriangleMesh load_mesh(const std::filesystem::path& path);

/// Loads the first node with a mesh of a glTF file with its skin (JOINTS_0/WEIGHTS_0, inverse
/// bind matrices), morph targets (POSITION deltas), node hierarchy and animations (LINEAR, STEP,
/// CUBICSPLINE), for jade/deform.hpp. Only TRIANGLES primitives; errors as load_mesh.
AnimatedMesh load_animated_gltf(const std::filesystem::path& path);

/// Writes an animated image (frames of width × height linear-RGB RGBA floats, sRGB-encoded,
/// 8 bit) at `fps` frames per second (0 < fps ≤ 100; GIF stores a delay in 1/100 s) as a looping
/// .gif (OpenImageIO's GIF writer, one subimage per frame; its WebP writer cannot animate).
/// Atomic like save_image.
void save_animation(const std::filesystem::path& path, int width, int height, const std::vector<std::vector<float>>& frames,
                    double fps);

/// Writes `bytes` to `path` atomically, as every file writer here does: a temporary file
/// "<path>.tmp-<pid>" in the same folder is written, synced to disk (fsync), renamed to `path`
/// and the folder synced. A failure or a crash at any moment leaves the old file (or none) or
/// the complete new one; a crash may leave the temporary file behind. Throws jade::Error
/// naming the file.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// What `jade bake` stores next to the mesh.
struct BakedAttributes {
    std::vector<float> ao;            ///< per render vertex, [0,1]
    std::vector<glm::vec3> tm;        ///< per render vertex, linear RGB, unitless
    std::vector<float> thickness;     ///< per render vertex, mesh units (empty: not written)
    std::string extras_json;          ///< a JSON object stored as the asset's `extras`
};

/// Writes `mesh` as binary glTF (.glb) or glTF with embedded buffer (.gltf) with the extra
/// vertex attributes `_AO` (SCALAR float), `_TM` (VEC3 float) and `_THICKNESS` (SCALAR float,
/// mesh units). Written to a temporary file
/// in the same folder and renamed, so a failure never leaves a half-written file.
void save_baked_gltf(const std::filesystem::path& path, const TriangleMesh& mesh, const BakedAttributes& baked);

/// Writes a linear-RGB float image: .png (sRGB-encoded, 8 bit), .exr (linear half/float).
/// `rgba` holds width*height*4 floats, rows top to bottom. Atomic like save_baked_gltf.
/// Alpha is straight (not premultiplied) and stored linearly; PNG values are clamped to [0,1].
void save_image(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgba);

/// An image read by load_image: linear RGBA floats, rows top to bottom.
struct LoadedImage {
    int width = 0, height = 0;
    std::vector<float> rgba;  ///< width*height*4, linear (8-bit files are sRGB-decoded; alpha as stored)
    bool srgb_8bit = false;   ///< the file held 8-bit sRGB values (PNG), decoded here
};

/// Reads a .png (8-bit sRGB, decoded to linear with the IEC 61966-2-1 curve) or .exr (linear)
/// through OpenImageIO; 1 to 4 channels (grey is copied to RGB, missing alpha is 1). Throws
/// jade::Error naming the file.
LoadedImage load_image(const std::filesystem::path& path);

}  // namespace jade
