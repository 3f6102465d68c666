// io/gltf_materials.hpp - Jade's reading of glTF materials (private to jade_io), shared by
// load_scene (io/scene_gltf.cpp) and the bake of a whole asset (io/gltf_asset.cpp).
//
//   translucent  iff KHR_materials_diffuse_transmission has diffuseTransmissionFactor > 0, or
//                extras.jade.preset names a preset; otherwise opaque (Lambert)
//   albedo       pbrMetallicRoughness.baseColorFactor (rgb, clamped to [0, 1])
//   roughness    pbrMetallicRoughness.roughnessFactor
//   strength     diffuseTransmissionFactor × extras.jade.strength (default 1)
//   medium       extras.jade.preset (with extras.jade.mm_per_unit, default 1000: glTF is in
//                metres) when given; else the medium of medium_from_appearance (jade/material.hpp)
//                with per channel c the extinction mean free path
//                  ℓ_c = L · T_c / (1 − ln a_c)      metres (= mesh units)
//                and the albedo A, through Material::from_medium (profile, transmission); L =
//                KHR_materials_volume.attenuationDistance (default 0.01 m), a = attenuationColor
//                clamped to [1e-4, 1], T = diffuseTransmissionColorFactor clamped to [1e-3, 1],
//                η = KHR_materials_ior.ior (default 1.5).
//   extras.jade.opaque = true forces Lambert.
// Every value that is out of range, of the wrong type or contradicts another gets a warning
// naming the file, the material (index and name) and the value, and the fallback in the table
// (docs/scene.md).
#pragma once

#include <jade/material.hpp>

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace jade::io {

class MaterialMapper {
public:
    MaterialMapper(const std::string& file, const tinygltf::Model& model, std::vector<std::string>* warnings)
        : file_(file), model_(model), warnings_(warnings)
    {
    }

    /// Material `index` of the model (-1: glTF's default material, white and opaque). Throws
    /// jade::Error naming the file and the material for an index that does not exist or a
    /// medium Material::from_medium refuses.
    Material map(int index);

private:
    void warn(const std::string& what);
    const tinygltf::Value* extension(const tinygltf::Material& g, const char* name);
    double number(const std::string& what, const tinygltf::Value& v, double fallback);
    double positive(const std::string& what, const tinygltf::Value& v, double fallback);
    double clamped(const std::string& what, double x, double lo, double hi, double fallback);
    glm::dvec3 color(const std::string& what, const tinygltf::Value& ext, double lo);

    const std::string& file_;
    const tinygltf::Model& model_;
    std::vector<std::string>* warnings_;
    std::string where_;
};

}  // namespace jade::io
