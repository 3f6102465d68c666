// io/gltf_asset.hpp - what a GltfAsset holds (private to jade_io): the document as read, twice.
//
// The JSON text is kept as nlohmann::ordered_json, so that every property, extension and extras
// the writer does not touch is written back as it was (key order included); tinygltf's parse of
// the same text provides the checked binary data (buffers, external files, accessors). Both see
// the same arrays, so their indices agree.
#pragma once

#include <jade/io.hpp>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace jade {

// What jade_io's sources call the private GltfAsset::Impl.
struct GltfAssetAccess {
    using Impl = GltfAsset::Impl;
    static const Impl& impl(const GltfAsset& asset) { return *asset.impl_; }
};
using GltfAssetImpl = GltfAssetAccess::Impl;

struct GltfAsset::Impl {
    /// Where a primitive's vertices lie in its target's merged mesh.
    struct Span {
        size_t first = 0, count = 0;
        bool baked = false;  ///< false: not a triangle primitive, never written to
    };

    std::filesystem::path path;
    std::string name;
    nlohmann::ordered_json doc;
    tinygltf::Model model;
    std::vector<std::vector<unsigned char>> image_bytes;  ///< per image, as tinygltf read it
    std::vector<std::filesystem::path> files;             ///< the asset, then what it read (GltfAsset::files)
    std::vector<BakeTarget> targets;
    std::vector<std::vector<Span>> spans;  ///< per target, per primitive of its mesh
    /// Per target: mesh units (the glTF mesh's own coordinates) per unit of the space it was baked
    /// in, 1 / the cube root of |det| of its first instance's world matrix (exact for a uniform scale).
    std::vector<double> mesh_units_per_bake_unit;
    std::vector<std::optional<Material>> translucent;  ///< per glTF material: Jade's, when translucent
};

}  // namespace jade
