// io/gltf_translucency.hpp - the JADE_materials_translucency glTF material extension (private to
// jade_io): a Jade Material as JSON and back, the one place that knows its property names.
// Schema: docs/schema/JADE_materials_translucency.schema.json; meaning: docs/gltf.md.
#pragma once

#include <jade/material.hpp>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <string>

namespace jade::io {

inline constexpr const char* kTranslucencyExtension = "JADE_materials_translucency";

/// Every parameter the renderer takes from `m` (albedo, strength, spread strength, specular
/// lobe, boundary transmittance, transmission, profiles), lengths in mesh units. Floats are
/// written as the doubles they are, so they read back bit for bit. Throws jade::Error naming
/// `file` for a value that is not finite.
nlohmann::ordered_json translucency_extension(const std::string& file, const Material& m);

/// The Material an extension object describes, every value checked (finite, in range, of the
/// right type); a bad one is a jade::Error naming `file`, `where` ("material 2") and the
/// property ("transmission.sigmaT[1]").
Material material_from_translucency(const std::string& file, const std::string& where, const nlohmann::json& ext);

/// A tinygltf value (an extension as tinygltf parsed it) as JSON.
nlohmann::json to_json(const tinygltf::Value& v);

}  // namespace jade::io
