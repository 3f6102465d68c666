// jade/io.hpp - file formats. Part of the separate target jade::io (links tinygltf,
// tinyobjloader, OpenImageIO); the core library jade::jade reads and writes no files.
// Every writer here is atomic: it writes a temporary file in the same folder, syncs it and
// renames it over `path`, so a failure or a crash leaves the old file (or none) or the complete
// new one (the writer itself: dev::write_file_atomically, jade/dev/io.hpp).
#pragma once

#include <jade/deform.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/scene.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace jade {

/// How the readers treat what a file points to.
struct ReadOptions {
    /// A glTF's external buffers and images are read only from its folder and below. The URI is
    /// judged lexically and then by the real path of its target (symbolic links resolved, in the
    /// URI and in the folder): a link inside the folder that leads out of it is refused unless
    /// this is set (a shared asset must not carry files from the machine that baked it).
    bool allow_outside_links = false;
    /// Receives what a reader repaired, naming the file (load_mesh: normals that are not finite
    /// or zero, recomputed from the triangles). Not owned; may be null.
    std::vector<std::string>* warnings = nullptr;
    /// load_mesh of a glTF file written by `jade bake`: receives the material it was baked with
    /// (the `JADE_materials_translucency` extension of the glTF material of the first triangle
    /// primitive read, docs/gltf.md), or nullopt when that material has none. Its values are
    /// checked (finite, in range; an error names the file, the material and the property).
    /// Not owned; may be null.
    std::optional<Material>* baked_material = nullptr;
};

/// Loads a triangle mesh, choosing the reader by extension (case-insensitive):
///   .gltf / .glb  glTF 2.0: every triangle primitive of the default scene (or scene 0), node
///                 transforms applied, indexed or not; reads `_AO`/`_TM`/`_THICKNESS`/
///                 `_SCATTERING_NORMAL`/`_NORMAL_SPREAD` if present (docs/gltf.md).
///   .off          OFF (polygons are fan-triangulated)
///   .ply          PLY, ASCII or binary little-endian (faces fan-triangulated)
///   .obj          Wavefront OBJ (via tinyobjloader)
/// Throws jade::Error naming the file, the element and what is wrong; never returns a partly
/// read mesh. Header counts are checked against the file size before anything is allocated.
TriangleMesh load_mesh(const std::filesystem::path& path, const ReadOptions& options = {});

/// Loads the first node with a mesh of a glTF file with its skin (JOINTS_0/WEIGHTS_0, inverse
/// bind matrices), morph targets (POSITION deltas), node hierarchy and animations (LINEAR, STEP,
/// CUBICSPLINE), for jade/deform.hpp, and the baked `_AO`/`_TM`/`_THICKNESS` of the bind pose
/// when every primitive has them (a file written by jade bake). Only TRIANGLES primitives;
/// errors as load_mesh.
AnimatedMesh load_animated_gltf(const std::filesystem::path& path, const ReadOptions& options = {});

/// Writes an animated image (frames of width × height linear-RGB RGBA floats, sRGB-encoded,
/// 8 bit) at `fps` frames per second (0 < fps ≤ 100; GIF stores a delay in 1/100 s) as a looping
/// .gif (OpenImageIO's GIF writer, one subimage per frame; its WebP writer cannot animate).
/// Atomic like save_image.
void save_animation(const std::filesystem::path& path, int width, int height,
                    const std::vector<std::vector<float>>& frames, double fps);

/// What `jade bake` stores next to the mesh: every per-vertex input of the default shading and
/// the material it was baked with (docs/gltf.md).
struct BakedAttributes {
    std::vector<float> ao;         ///< per render vertex, [0,1]
    std::vector<glm::vec3> tm;     ///< per render vertex, linear RGB, unitless
    std::vector<float> thickness;  ///< per render vertex, mesh units (empty: not written)
    /// Per render vertex, unit length, in the space the mesh was baked in (BakeResult::
    /// scattering_normal); empty: not written.
    std::vector<glm::vec3> scattering_normal;
    std::vector<glm::vec3> normal_spread;  ///< per render vertex and channel, [0, 1] (empty: not written)
    /// The material the values were baked with, lengths in the mesh units of the bake; written
    /// as the glTF material's `JADE_materials_translucency` extension. Empty (or opaque): none.
    std::optional<Material> material;
    std::string extras_json;  ///< a JSON object stored as the asset's `extras`
};

/// Writes `mesh` as binary glTF (.glb) or glTF with embedded buffer (.gltf) with the extra
/// vertex attributes `_AO` (SCALAR float), `_TM` (VEC3 float), `_THICKNESS` (SCALAR float,
/// mesh units), `_SCATTERING_NORMAL` (VEC3 float) and `_NORMAL_SPREAD` (VEC3 float), each where
/// given, and one material carrying `baked.material` as `JADE_materials_translucency`. Written
/// to a temporary file in the same folder and renamed, so a failure never leaves a half-written
/// file.
void save_baked_gltf(const std::filesystem::path& path, const TriangleMesh& mesh, const BakedAttributes& baked);

/// A glTF 2.0 asset (.gltf or .glb) read whole, to be written back with baked attributes by
/// save_baked_asset: every scene, node, mesh, material, texture, image, sampler, skin, animation,
/// camera, extension and extras as read (docs/gltf.md). What is baked, the instance rule:
/// - each glTF mesh once, all its triangle primitives together as one surface (they occlude and
///   scatter into each other), in the world space of its first instance in the default scene
///   (depth-first, as load_mesh walks it), node scale included; every other instance gets the
///   same values. A mesh whose first instance has a skin is baked in its bind pose (the
///   positions as stored, which the skin deforms); one no node of the default scene shows, in
///   its own coordinates. Morph targets are at weight 0 (the base shape, as load_mesh reads it).
/// - primitives whose glTF material Jade maps translucent (docs/scene.md) are baked with that
///   material, the others (opaque, or no material) with the caller's: one target per distinct
///   material of a mesh, each over the whole mesh.
/// - POINTS and LINES primitives are written back unchanged, without baked attributes.
class GltfAsset {
public:
    struct BakeTarget {
        /// The mesh's triangle primitives merged, in the space above (mesh units); render
        /// vertices in primitive order, each primitive's in its own vertex order. Named
        /// "FILE: mesh 3 'wheel'" for messages.
        TriangleMesh mesh;
        int mesh_index = -1;
        std::vector<int> primitives;  ///< the primitives of the mesh that take this bake's values
        /// Jade's material for them when their glTF material is translucent; empty: the caller's.
        std::optional<Material> material;
        std::string material_name;  ///< "material 2 'steel'" or "no material"
        std::string space;          ///< "world space of node 4 'wheel' (first of 2 instances)", ...
    };

    /// Reads the file (errors as load_mesh, naming the file and the element). External buffers
    /// and images must exist: the output holds them. `warnings` receives what the material
    /// mapping says (docs/scene.md).
    static GltfAsset load(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr,
                          const ReadOptions& options = {});

    GltfAsset(GltfAsset&&) noexcept;
    GltfAsset& operator=(GltfAsset&&) noexcept;
    ~GltfAsset();

    const std::vector<BakeTarget>& targets() const;

private:
    struct Impl;
    friend struct GltfAssetAccess;  // names Impl for jade_io's own sources (io/gltf_asset.hpp)
    friend void save_baked_asset(const std::filesystem::path&, const GltfAsset&, const std::vector<BakedAttributes>&,
                                 const std::string&);
    explicit GltfAsset(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

/// Writes `asset` to `path` (.glb or .gltf, whatever the input was) with `baked[i]` - one
/// BakedAttributes per asset.targets()[i], over its mesh's render vertices; empty ao and tm:
/// target not baked; their extras_json is not used - added to the target's primitives as the
/// vertex attributes `_AO` (SCALAR float), `_TM` (VEC3 float), `_THICKNESS` (SCALAR float,
/// mesh units), `_SCATTERING_NORMAL` and `_NORMAL_SPREAD` (VEC3 float; the last three only where
/// given), replacing earlier ones. Each baked primitive's glTF material gets the target's
/// `material` as `JADE_materials_translucency` (the first target's where several share one glTF
/// material), and, for primitives with TEXCOORD_0 and a thickness, a thickness map in
/// `KHR_materials_volume.thicknessTexture` (docs/gltf.md: size rule, seams, what else is added). `asset_extras_json`, a JSON object, is
/// merged into the asset's `extras` (its keys replace the same keys). Besides: the output is one
/// self-contained file (external buffers and images embedded; all buffers packed into one, each
/// bufferView 4-byte aligned); required accessor bounds the input lacks (POSITION, animation key
/// times) are added; materials that Jade maps translucent without KHR_materials_diffuse_transmission
/// (an extras.jade.preset) get it and KHR_materials_volume with the preset's medium. Every value
/// written is finite: a non-finite baked value is an error naming the file, mesh, primitive and
/// vertex. Atomic (the header comment): `path` may be the asset's own file.
void save_baked_asset(const std::filesystem::path& path, const GltfAsset& asset,
                      const std::vector<BakedAttributes>& baked, const std::string& asset_extras_json);

/// Writes a linear-RGB float image: .png (sRGB-encoded, 8 bit), .exr (linear half/float).
/// `rgba` holds width*height*4 floats, rows top to bottom. Atomic like save_baked_gltf.
/// Alpha is straight (not premultiplied) and stored linearly; PNG values are clamped to [0,1].
void save_image(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgba);

/// A scene file (.gltf / .glb): one object per triangle primitive of each mesh instance of the
/// default scene, in world space, with its material mapped as docs/scene.md says
/// (KHR_materials_volume, KHR_materials_diffuse_transmission, baseColorFactor and
/// extras.jade). Warnings about unknown or contradictory values (each names the file, the
/// material and the value, and the fallback taken) go to `warnings`. Throws jade::Error naming
/// the file and element for malformed files.
Scene load_scene(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr,
                 const ReadOptions& options = {});

}  // namespace jade
