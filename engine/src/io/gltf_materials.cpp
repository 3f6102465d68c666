// io/gltf_materials.cpp - Jade's reading of glTF materials; see gltf_materials.hpp.
#include "io/gltf_materials.hpp"

#include "io/common.hpp"

#include <jade/error.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace jade::io {
namespace {

constexpr double kDefaultMeanFreePath = 0.01;  // metres: 1 cm, when the file gives no length

std::string num(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

Material MaterialMapper::map(int index)
{
    if (index < 0) {
        Material m = material_preset("opaque", 1000.0);
        m.name = "(no material)";
        m.albedo = glm::vec3(1.0f);  // glTF's default material: white, Lambert
        return m;
    }
    if (size_t(index) >= model_.materials.size())
        fail(file_, "material " + std::to_string(index) + " does not exist (" +
                        std::to_string(model_.materials.size()) + " materials)");
    const tinygltf::Material& g = model_.materials[size_t(index)];
    where_ = "material " + std::to_string(index) + (g.name.empty() ? "" : " '" + g.name + "'");

    glm::dvec3 albedo(1.0);
    const auto& base = g.pbrMetallicRoughness.baseColorFactor;
    if (base.size() >= 3)
        for (int c = 0; c < 3; ++c)
            albedo[c] = clamped("baseColorFactor[" + std::to_string(c) + "]", base[size_t(c)], 0.0, 1.0, 1.0);

    // Jade's own parameters.
    std::string preset;
    double mm_per_unit = 1000.0, strength = 1.0;
    bool force_opaque = false;
    if (g.extras.Has("jade")) {
        const tinygltf::Value& j = g.extras.Get("jade");
        if (!j.IsObject())
            warn("extras.jade is not an object; ignored");
        else
            for (const std::string& key : j.Keys()) {
                const tinygltf::Value& v = j.Get(key);
                if (key == "preset") {
                    if (!v.IsString())
                        warn("extras.jade.preset is not a string; ignored");
                    else
                        preset = v.Get<std::string>();
                } else if (key == "mm_per_unit") {
                    mm_per_unit = positive("extras.jade.mm_per_unit", v, 1000.0);
                } else if (key == "strength") {
                    strength = number("extras.jade.strength", v, 1.0);
                    if (strength < 0)
                        warn("extras.jade.strength " + num(strength) + " is negative; 1 used"), strength = 1.0;
                    // Beyond this the blur is flat anyway, and the product with the material's
                    // blur would overflow single precision.
                    if (strength > 1e6)
                        warn("extras.jade.strength " + num(strength) + " is above 1e6; 1e6 used"), strength = 1e6;
                } else if (key == "opaque") {
                    if (!v.IsBool())
                        warn("extras.jade.opaque is not true or false; ignored");
                    else
                        force_opaque = v.Get<bool>();
                } else {
                    warn("extras.jade." + key +
                         " is not a Jade parameter (preset, mm_per_unit, strength, opaque); ignored");
                }
            }
    }
    if (!preset.empty()) {
        const auto names = material_preset_names();
        if (std::find(names.begin(), names.end(), preset) == names.end()) {
            std::string list;
            for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
            warn("extras.jade.preset '" + printable(preset, 32) + "' is unknown (known: " + list +
                 "); the glTF extensions decide the profile");
            preset.clear();
        }
    }

    // KHR_materials_diffuse_transmission.
    double transmission = 0.0;
    glm::dvec3 transmission_color(1.0);
    const tinygltf::Value* dt = extension(g, "KHR_materials_diffuse_transmission");
    if (dt) {
        transmission =
            dt->Has("diffuseTransmissionFactor")
                ? clamped("diffuseTransmissionFactor",
                          number("diffuseTransmissionFactor", dt->Get("diffuseTransmissionFactor"), 0.0), 0.0, 1.0, 0.0)
                : 0.0;
        transmission_color = color("diffuseTransmissionColorFactor", *dt, 1e-3);
    }

    // KHR_materials_ior.
    double ior = 1.5;
    if (const tinygltf::Value* e = extension(g, "KHR_materials_ior"); e && e->Has("ior")) {
        ior = number("KHR_materials_ior.ior", e->Get("ior"), 1.5);
        if (!(ior > 0.2 && ior < 5.0))
            warn("KHR_materials_ior.ior " + num(ior) + " is outside (0.2, 5); 1.5 used"), ior = 1.5;
    }

    // KHR_materials_volume.
    double distance = kDefaultMeanFreePath;
    glm::dvec3 attenuation(1.0);
    const tinygltf::Value* vol = extension(g, "KHR_materials_volume");
    if (vol) {
        double thickness =
            vol->Has("thicknessFactor") ? number("thicknessFactor", vol->Get("thicknessFactor"), 0.0) : 0.0;
        if (thickness < 0)
            warn("KHR_materials_volume.thicknessFactor " + num(thickness) + " is negative; 0 used"), thickness = 0;
        if (!dt || transmission == 0.0) {
            if (preset.empty())
                warn("KHR_materials_volume without diffuse transmission (KHR_materials_diffuse_transmission with "
                     "diffuseTransmissionFactor > 0): the volume has no effect in glTF; drawn opaque (Lambert)");
        } else if (thickness == 0.0) {
            warn("KHR_materials_volume.thicknessFactor is 0 (thin-walled in glTF: no volume); attenuation ignored, "
                 "default mean free path 0.01 m used");
        } else {
            if (vol->Has("attenuationDistance")) {
                const double d = number("attenuationDistance", vol->Get("attenuationDistance"), kDefaultMeanFreePath);
                if (!(d > 0.0) || !std::isfinite(d))
                    warn("KHR_materials_volume.attenuationDistance " + num(d) +
                         " is not a positive finite length; "
                         "0.01 m used");
                else
                    distance = d;
            }
            attenuation = color("attenuationColor", *vol, 1e-4);
        }
    }

    Material m;
    const bool translucent = !force_opaque && (transmission > 0.0 || !preset.empty());
    if (!preset.empty()) {
        m = material_preset(preset, mm_per_unit);
        if (!preset.empty() && transmission == 0.0 && dt)
            warn("diffuseTransmissionFactor is 0 but extras.jade.preset is '" + preset +
                 "'; the preset is used with strength " + num(strength));
        if (transmission > 0.0) strength *= transmission;
    } else if (translucent) {
        // The medium whose derived diffuse colour is the base colour, with the mean free path
        // of the table above (Material::from_medium, jade/material.hpp).
        glm::dvec3 mfp;
        for (int c = 0; c < 3; ++c) mfp[c] = distance * transmission_color[c] / (1.0 - std::log(attenuation[c]));
        const double roughness = clamped("roughnessFactor", g.pbrMetallicRoughness.roughnessFactor, 0.0, 1.0, 1.0);
        try {
            m = Material::from_medium(medium_from_appearance(albedo, mfp, ior, roughness));
        } catch (const Error& e) {
            throw Error(file_ + ": " + where_ + ": " + e.what());
        }
        strength *= transmission;
    } else {
        m = material_preset("opaque", 1000.0);
    }
    m.name = g.name.empty() ? "material " + std::to_string(index) : g.name;
    m.albedo = glm::vec3(albedo);
    m.roughness = float(clamped("roughnessFactor", g.pbrMetallicRoughness.roughnessFactor, 0.0, 1.0, 1.0));
    // extras.jade.strength (times the diffuse transmission factor) scales the material's blur: the
    // poster's scale-free part and the spread's part alike.
    m.strength *= float(strength);
    m.spread_strength *= float(strength);
    m.opaque = !translucent;
    return m;
}

void MaterialMapper::warn(const std::string& what)
{
    if (warnings_) warnings_->push_back(file_ + ": " + where_ + ": " + what);
}

const tinygltf::Value* MaterialMapper::extension(const tinygltf::Material& g, const char* name)
{
    auto it = g.extensions.find(name);
    if (it == g.extensions.end()) return nullptr;
    if (!it->second.IsObject()) {
        warn(std::string(name) + " is not an object; ignored");
        return nullptr;
    }
    return &it->second;
}

double MaterialMapper::number(const std::string& what, const tinygltf::Value& v, double fallback)
{
    if (v.IsNumber() && std::isfinite(v.GetNumberAsDouble())) return v.GetNumberAsDouble();
    warn(what + " is not a finite number; " + num(fallback) + " used");
    return fallback;
}

double MaterialMapper::positive(const std::string& what, const tinygltf::Value& v, double fallback)
{
    const double x = number(what, v, fallback);
    if (x > 0) return x;
    warn(what + " " + num(x) + " is not positive; " + num(fallback) + " used");
    return fallback;
}

double MaterialMapper::clamped(const std::string& what, double x, double lo, double hi, double fallback)
{
    if (!std::isfinite(x)) {
        warn(what + " is not finite; " + num(fallback) + " used");
        return fallback;
    }
    if (x < lo || x > hi) {
        const double c = std::min(std::max(x, lo), hi);
        warn(what + " " + num(x) + " is outside [" + num(lo) + ", " + num(hi) + "]; " + num(c) + " used");
        return c;
    }
    return x;
}

/// An RGB factor of an extension (default white), each channel clamped to [lo, 1].
glm::dvec3 MaterialMapper::color(const std::string& what, const tinygltf::Value& ext, double lo)
{
    glm::dvec3 out(1.0);
    if (!ext.Has(what)) return out;
    const tinygltf::Value& v = ext.Get(what);
    if (!v.IsArray() || v.ArrayLen() != 3) {
        warn(what + " is not an array of 3 numbers; white used");
        return out;
    }
    for (int c = 0; c < 3; ++c) {
        const std::string name = what + "[" + std::to_string(c) + "]";
        out[c] = clamped(name, number(name, v.Get(c), 1.0), 0.0, 1.0, 1.0);
        if (out[c] < lo) {
            warn(name + " " + num(out[c]) + " is below " + num(lo) + " (no light would pass); " + num(lo) + " used");
            out[c] = lo;
        }
    }
    return out;
}

}  // namespace jade::io
