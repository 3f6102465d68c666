// io/gltf_asset_materials.cpp - the materials of a baked asset; see the header.
#include "io/gltf_asset_materials.hpp"

#include "io/common.hpp"
#include "io/gltf_accessors.hpp"
#include "io/gltf_thickness_map.hpp"
#include "io/gltf_translucency.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <jade/dev/material.hpp>

namespace jade::io {

namespace {

using json = nlohmann::ordered_json;

int material_of(const MaterialEdits& e, size_t t, size_t p)
{
    return e.asset.model.meshes[size_t(e.asset.targets[t].mesh_index)].primitives[p].material;
}

/// TEXCOORD_0 of primitive p of target t (FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT,
/// as glTF allows), or empty when it has none.
std::vector<glm::vec2> texcoords(const MaterialEdits& e, size_t t, size_t p)
{
    const auto& prim = e.asset.model.meshes[size_t(e.asset.targets[t].mesh_index)].primitives[p];
    const auto it = prim.attributes.find("TEXCOORD_0");
    if (it == prim.attributes.end()) return {};
    const AccessorReader reader(e.asset.name, e.asset.model);
    const auto view = reader.view(
        "mesh " + std::to_string(e.asset.targets[t].mesh_index) + " primitive " + std::to_string(p) + ": ", it->second,
        {"TEXCOORD_0",
         TINYGLTF_TYPE_VEC2,
         {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}});
    std::vector<glm::vec2> uv(view.count);
    for (size_t i = 0; i < view.count; ++i) {
        if (view.component == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            view.bytes(i, &uv[i], sizeof(glm::vec2));
        } else if (view.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            uint8_t b[2];
            view.bytes(i, b, sizeof b);
            uv[i] = glm::vec2(b[0], b[1]) / 255.0f;
        } else {
            uint16_t s[2];
            view.bytes(i, s, sizeof s);
            uv[i] = glm::vec2(s[0], s[1]) / 65535.0f;
        }
    }
    return uv;
}

/// j[key], or null when j is no object or lacks it (no copy, no key added).
const json& at(const json& j, const char* key)
{
    static const json none;
    if (!j.is_object()) return none;
    const auto it = j.find(key);
    return it == j.end() ? none : *it;
}

/// j[key] as an int, or -1 when j is no object, lacks it or it is no integer.
int as_int(const json& j, const char* key)
{
    const json& v = at(j, key);
    return v.is_number_integer() ? v.get<int>() : -1;
}

/// The texture of material m's thickness map from an earlier bake (its KHR_materials_volume
/// thicknessTexture, whose image is named kThicknessMapName), or -1.
int earlier_map(const MaterialEdits& e, int m)
{
    const json& doc = e.doc;
    const json& volume = at(at(doc["materials"][size_t(m)], "extensions"), "KHR_materials_volume");
    const int texture = as_int(at(volume, "thicknessTexture"), "index");
    const json &textures = at(doc, "textures"), &images = at(doc, "images");
    if (texture < 0 || size_t(texture) >= textures.size()) return -1;
    const int image = as_int(textures[size_t(texture)], "source");
    if (image < 0 || size_t(image) >= images.size()) return -1;
    const json& name = at(images[size_t(image)], "name");
    return name.is_string() && name.get<std::string>().rfind(kThicknessMapName, 0) == 0 ? texture : -1;
}

}  // namespace

void use_extension(json& doc, const char* name)
{
    json& used = doc["extensionsUsed"];
    if (!used.is_array()) used = json::array();
    if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
}

void mark_translucent(const MaterialEdits& e)
{
    const GltfAssetImpl& a = e.asset;
    const auto& baked = e.baked;
    for (size_t m = 0; m < a.translucent.size(); ++m) {
        json& material = e.doc["materials"][m];
        if (!a.translucent[m] ||
            (material.contains("extensions") && material["extensions"].contains("KHR_materials_diffuse_transmission")))
            continue;
        const Material& jade = *a.translucent[m];
        glm::dvec3 mfp;
        for (int c = 0; c < 3; ++c)
            mfp[c] = jade.transmission.sigma_t[c] > 0.0f
                         ? 1.0 / double(jade.transmission.sigma_t[c])
                         : dev::radius_for_tail(jade.profile[size_t(c)], std::exp(-1.0));
        const double distance = std::max({mfp.x, mfp.y, mfp.z});
        double sum = 0.0;
        size_t n = 0;
        for (size_t t = 0; t < baked.size(); ++t)
            for (size_t p = 0; p < a.spans[t].size(); ++p)
                if (a.spans[t][p].baked && !baked[t].thickness.empty() &&
                    a.model.meshes[size_t(a.targets[t].mesh_index)].primitives[p].material == int(m))
                    for (size_t v = 0; v < a.spans[t][p].count; ++v)
                        sum += baked[t].thickness[a.spans[t][p].first + v], ++n;
        const double thickness = n && sum > 0.0 ? sum / double(n) : distance;
        json color = json::array();
        for (int c = 0; c < 3; ++c) color.push_back(std::exp(1.0 - distance / mfp[c]));
        if (!(std::isfinite(distance) && distance > 0.0 && std::isfinite(thickness)))
            fail(a.name, "material " + std::to_string(m) + ": the preset's mean free path " + std::to_string(distance) +
                             " cannot be written as KHR_materials_volume");
        json& extensions = material["extensions"];
        if (!extensions.is_object()) extensions = json::object();
        extensions["KHR_materials_diffuse_transmission"] = {{"diffuseTransmissionFactor", 1.0}};
        if (!extensions.contains("KHR_materials_volume"))
            extensions["KHR_materials_volume"] = {
                {"thicknessFactor", thickness}, {"attenuationDistance", distance}, {"attenuationColor", color}};
        // Last: adding extensionsUsed to the document moves its members (references above dangle).
        use_extension(e.doc, "KHR_materials_diffuse_transmission");
        use_extension(e.doc, "KHR_materials_volume");
    }
}

void add_translucency_extensions(const MaterialEdits& e)
{
    std::vector<bool> written(e.asset.model.materials.size(), false);
    int added = -1;  // the material made for the baked primitives without one
    for (size_t t = 0; t < e.baked.size(); ++t) {
        const auto& material = e.baked[t].material;
        if (!material || material->opaque || e.baked[t].ao.empty()) continue;
        for (size_t p = 0; p < e.asset.spans[t].size(); ++p) {
            const int m = material_of(e, t, p);
            if (!e.asset.spans[t][p].baked) continue;
            if (m < 0) {
                if (added < 0) {
                    if (!e.doc["materials"].is_array()) e.doc["materials"] = json::array();
                    e.doc["materials"].push_back(
                        {{"name", kBakeMaterialName},
                         {"extensions", {{kTranslucencyExtension, translucency_extension(e.asset.name, *material)}}}});
                    added = int(e.doc["materials"].size() - 1);
                    use_extension(e.doc, kTranslucencyExtension);
                }
                e.doc["meshes"][size_t(e.asset.targets[t].mesh_index)]["primitives"][p]["material"] = added;
                continue;
            }
            if (written[size_t(m)]) continue;
            json& extensions = e.doc["materials"][size_t(m)]["extensions"];
            if (!extensions.is_object()) extensions = json::object();
            extensions[kTranslucencyExtension] = translucency_extension(e.asset.name, *material);
            use_extension(e.doc, kTranslucencyExtension);
            written[size_t(m)] = true;
        }
    }
}

void add_thickness_maps(const MaterialEdits& e)
{
    std::map<int, UvTriangles> per_material;
    for (size_t t = 0; t < e.baked.size(); ++t) {
        if (e.baked[t].thickness.empty()) continue;
        const TriangleMesh& mesh = e.asset.targets[t].mesh;
        for (size_t p = 0; p < e.asset.spans[t].size(); ++p) {
            const auto& span = e.asset.spans[t][p];
            const int m = material_of(e, t, p);
            if (!span.baked || m < 0) continue;
            const json& material = std::as_const(e.doc)["materials"][size_t(m)];  // const: adds no keys
            const auto ext = material.find("extensions");
            if (ext == material.end() || !ext->is_object() ||
                (!ext->contains("KHR_materials_transmission") && !ext->contains("KHR_materials_diffuse_transmission")))
                continue;
            const std::vector<glm::vec2> uv = texcoords(e, t, p);
            if (uv.size() != span.count) continue;  // no TEXCOORD_0 (a count mismatch is the validator's to name)
            UvTriangles& out = per_material[m];
            const uint32_t base = uint32_t(out.positions.size());
            out.positions.insert(out.positions.end(), mesh.positions.begin() + std::ptrdiff_t(span.first),
                                 mesh.positions.begin() + std::ptrdiff_t(span.first + span.count));
            out.uv.insert(out.uv.end(), uv.begin(), uv.end());
            // KHR_materials_volume's thickness is in the mesh's own coordinates (the node's transform
            // applies to it); the bake's is in the space of the mesh's first instance.
            for (size_t v = span.first; v < span.first + span.count; ++v)
                out.thickness.push_back(float(e.baked[t].thickness[v] * e.asset.mesh_units_per_bake_unit[t]));
            // The primitive's triangles: those of the merged mesh within its vertex span.
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
                if (mesh.indices[i] >= span.first && mesh.indices[i] < span.first + span.count)
                    for (int k = 0; k < 3; ++k)
                        out.indices.push_back(base + uint32_t(mesh.indices[i + size_t(k)] - span.first));
        }
    }
    for (const auto& [m, triangles] : per_material) {
        const uint32_t size = thickness_map_size(triangles);
        if (size == 0) continue;  // a UV layout without area
        const ThicknessMap map = bake_thickness_map(triangles, size);
        if (!(map.factor > 0.0)) continue;  // thicknessFactor 0 would mean thin-walled
        // An earlier bake's map of this material is replaced where it is; else one is appended.
        const int previous = earlier_map(e, m);
        const int image_index = previous >= 0 ? e.doc["textures"][size_t(previous)]["source"].get<int>() : -1;
        json image = e.embed(encode_thickness_png(e.asset.name, map), "image/png", image_index);
        image["name"] = std::string(kThicknessMapName) + ", material " + std::to_string(m);
        // Linear filtering without mipmaps: the map is dilated a few texels only.
        const json sampler = {{"magFilter", 9729}, {"minFilter", 9729}};
        size_t texture_index = 0;
        if (previous >= 0) {
            e.doc["images"][size_t(image_index)] = std::move(image);
            texture_index = size_t(previous);
            const int s = as_int(std::as_const(e.doc)["textures"][texture_index], "sampler");
            if (s >= 0) e.doc["samplers"][size_t(s)] = sampler;
        } else {
            if (!e.doc["images"].is_array()) e.doc["images"] = json::array();
            e.doc["images"].push_back(std::move(image));
            if (!e.doc["samplers"].is_array()) e.doc["samplers"] = json::array();
            e.doc["samplers"].push_back(sampler);
            if (!e.doc["textures"].is_array()) e.doc["textures"] = json::array();
            e.doc["textures"].push_back(
                {{"source", e.doc["images"].size() - 1}, {"sampler", e.doc["samplers"].size() - 1}});
            texture_index = e.doc["textures"].size() - 1;
        }
        json& volume = e.doc["materials"][size_t(m)]["extensions"]["KHR_materials_volume"];
        if (!volume.is_object()) volume = json::object();
        volume["thicknessFactor"] = map.factor;
        volume["thicknessTexture"] = {{"index", texture_index}};
        use_extension(e.doc, "KHR_materials_volume");
    }
}

}  // namespace jade::io
