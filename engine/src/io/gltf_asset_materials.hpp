// io/gltf_asset_materials.hpp - what save_baked_asset adds to the materials of a baked asset
// (private to jade_io; docs/gltf.md): the translucency extensions other viewers read, Jade's own
// JADE_materials_translucency, and thickness maps in KHR_materials_volume.
#pragma once

#include "io/gltf_asset.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace jade::io {

/// The document being written and the writer's one way to add an image's bytes to it.
struct MaterialEdits {
    const GltfAssetImpl& asset;
    nlohmann::ordered_json& doc;
    const std::vector<BakedAttributes>& baked;
    /// The members of an image object holding the bytes (a bufferView in .glb, a data URI in .gltf);
    /// `replacing`: the index of an earlier thickness map's image whose view is reused, or -1.
    std::function<nlohmann::ordered_json(const std::vector<unsigned char>& bytes, const std::string& mime,
                                         int replacing)>
        embed;
};

/// Adds `name` to extensionsUsed (not Required: every extension here may be ignored). Adding the
/// array moves the document's members (ordered_json keeps them in a vector): a reference into
/// `doc` taken before does not survive it.
void use_extension(nlohmann::ordered_json& doc, const char* name);

/// KHR_materials_diffuse_transmission (factor 1: Jade's strength is unchanged) and
/// KHR_materials_volume for materials translucent through extras.jade.preset alone: the volume's
/// attenuation gives back the preset's extinction mean free path ℓ_c = 1/σ_t,c through the
/// mapping ℓ_c = L / (1 − ln a_c) of docs/scene.md, L = max ℓ_c; the thickness is the mean baked
/// thickness of the material's vertices (else L).
void mark_translucent(const MaterialEdits& e);

/// The name of the material made for baked primitives without one.
inline constexpr const char* kBakeMaterialName = "jade bake";

/// JADE_materials_translucency on the glTF material of every baked primitive: the Jade material
/// the primitive was baked with (the first target's where several targets share a glTF material;
/// the command line's material is the same for all of them, a translucent glTF material's own is
/// too). Baked primitives without a material get one of their own, named kBakeMaterialName, with
/// no property but the extension: other viewers draw it as glTF's default material, as before.
void add_translucency_extensions(const MaterialEdits& e);

/// The name of every thickness map's image: how a re-bake finds its own (and replaces it).
inline constexpr const char* kThicknessMapName = "jade thickness map";

/// A thickness map per glTF material whose baked primitives have TEXCOORD_0 and a thickness, in
/// its KHR_materials_volume (thicknessTexture, thicknessFactor), when the material transmits
/// light for other viewers (KHR_materials_transmission or KHR_materials_diffuse_transmission, as
/// KHR_materials_volume requires). Primitives without UVs keep the `_THICKNESS` attribute alone.
/// A map of an earlier bake (the material's thicknessTexture, an image named kThicknessMapName)
/// is replaced in place: its image, texture and sampler keep their indices.
void add_thickness_maps(const MaterialEdits& e);

}  // namespace jade::io
