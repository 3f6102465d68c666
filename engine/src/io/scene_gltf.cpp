// io/scene_gltf.cpp - jade::load_scene: a glTF file as a Jade scene, and cached_bakes().
//
// Objects: one per triangle primitive of each mesh instance (io/gltf.cpp read_gltf_primitives),
// in world space. Materials (docs/scene.md has the table and the derivation):
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
//   extras.jade.opaque = true forces Lambert. Node extras {"jade": {"deform": "bend"}} (or
//   twist, squash, wave; optional "axis" 0..2) make the node's objects deforming, with
//   ProceduralDeformer::fit.
// Every value that is out of range, of the wrong type or contradicts another gets a warning
// naming the file, the material (index and name) and the value, and the fallback in the table.
#include <jade/scene.hpp>

#include "io/common.hpp"
#include "io/gltf_model.hpp"

#include <jade/error.hpp>

#include <cmath>
#include <sstream>

namespace jade {
namespace {

constexpr double kDefaultMeanFreePath = 0.01;  // metres: 1 cm, when the file gives no length

std::string num(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

class MaterialMapper {
public:
    MaterialMapper(const std::string& file, const tinygltf::Model& model, std::vector<std::string>* warnings)
        : file_(file), model_(model), warnings_(warnings)
    {
    }

    Material map(int index)
    {
        if (index < 0) {
            Material m = material_preset("opaque", 1000.0);
            m.name = "(no material)";
            m.albedo = glm::vec3(1.0f);  // glTF's default material: white, Lambert
            return m;
        }
        if (size_t(index) >= model_.materials.size())
            io::fail(file_, "material " + std::to_string(index) + " does not exist (" + std::to_string(model_.materials.size()) +
                                " materials)");
        const tinygltf::Material& g = model_.materials[size_t(index)];
        where_ = "material " + std::to_string(index) + (g.name.empty() ? "" : " '" + g.name + "'");

        glm::dvec3 albedo(1.0);
        const auto& base = g.pbrMetallicRoughness.baseColorFactor;
        if (base.size() >= 3)
            for (int c = 0; c < 3; ++c) albedo[c] = clamped("baseColorFactor[" + std::to_string(c) + "]", base[size_t(c)], 0.0, 1.0, 1.0);

        // Jade's own parameters.
        std::string preset;
        double mm_per_unit = 1000.0, strength = 1.0;
        bool force_opaque = false;
        if (g.extras.Has("jade")) {
            const tinygltf::Value& j = g.extras.Get("jade");
            if (!j.IsObject()) warn("extras.jade is not an object; ignored");
            else
                for (const std::string& key : j.Keys()) {
                    const tinygltf::Value& v = j.Get(key);
                    if (key == "preset") {
                        if (!v.IsString()) warn("extras.jade.preset is not a string; ignored");
                        else preset = v.Get<std::string>();
                    } else if (key == "mm_per_unit") {
                        mm_per_unit = positive("extras.jade.mm_per_unit", v, 1000.0);
                    } else if (key == "strength") {
                        strength = number("extras.jade.strength", v, 1.0);
                        if (strength < 0) warn("extras.jade.strength " + num(strength) + " is negative; 1 used"), strength = 1.0;
                    } else if (key == "opaque") {
                        if (!v.IsBool()) warn("extras.jade.opaque is not true or false; ignored");
                        else force_opaque = v.Get<bool>();
                    } else {
                        warn("extras.jade." + key + " is not a Jade parameter (preset, mm_per_unit, strength, opaque); ignored");
                    }
                }
        }
        if (!preset.empty()) {
            const auto names = material_preset_names();
            if (std::find(names.begin(), names.end(), preset) == names.end()) {
                std::string list;
                for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
                warn("extras.jade.preset '" + io::printable(preset, 32) + "' is unknown (known: " + list +
                     "); the glTF extensions decide the profile");
                preset.clear();
            }
        }

        // KHR_materials_diffuse_transmission.
        double transmission = 0.0;
        glm::dvec3 transmission_color(1.0);
        const tinygltf::Value* dt = extension(g, "KHR_materials_diffuse_transmission");
        if (dt) {
            transmission = dt->Has("diffuseTransmissionFactor")
                               ? clamped("diffuseTransmissionFactor", number("diffuseTransmissionFactor", dt->Get("diffuseTransmissionFactor"), 0.0), 0.0, 1.0, 0.0)
                               : 0.0;
            transmission_color = color("diffuseTransmissionColorFactor", *dt, 1e-3);
        }

        // KHR_materials_ior.
        double ior = 1.5;
        if (const tinygltf::Value* e = extension(g, "KHR_materials_ior"); e && e->Has("ior")) {
            ior = number("KHR_materials_ior.ior", e->Get("ior"), 1.5);
            if (!(ior > 0.2 && ior < 5.0)) warn("KHR_materials_ior.ior " + num(ior) + " is outside (0.2, 5); 1.5 used"), ior = 1.5;
        }

        // KHR_materials_volume.
        double distance = kDefaultMeanFreePath;
        glm::dvec3 attenuation(1.0);
        const tinygltf::Value* vol = extension(g, "KHR_materials_volume");
        if (vol) {
            double thickness = vol->Has("thicknessFactor") ? number("thicknessFactor", vol->Get("thicknessFactor"), 0.0) : 0.0;
            if (thickness < 0) warn("KHR_materials_volume.thicknessFactor " + num(thickness) + " is negative; 0 used"), thickness = 0;
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
                        warn("KHR_materials_volume.attenuationDistance " + num(d) + " is not a positive finite length; "
                             "0.01 m used");
                    else distance = d;
                }
                attenuation = color("attenuationColor", *vol, 1e-4);
            }
        }

        Material m;
        const bool translucent = !force_opaque && (transmission > 0.0 || !preset.empty());
        if (!preset.empty()) {
            m = material_preset(preset, mm_per_unit);
            if (!preset.empty() && transmission == 0.0 && dt)
                warn("diffuseTransmissionFactor is 0 but extras.jade.preset is '" + preset + "'; the preset is used with strength " +
                     num(strength));
            if (transmission > 0.0) strength *= transmission;
        } else if (translucent) {
            // The medium whose derived diffuse colour is the base colour, with the mean free path
            // of the table above (Material::from_medium, jade/material.hpp).
            glm::dvec3 mfp;
            for (int c = 0; c < 3; ++c) mfp[c] = distance * transmission_color[c] / (1.0 - std::log(attenuation[c]));
            const double roughness = clamped("roughnessFactor", g.pbrMetallicRoughness.roughnessFactor, 0.0, 1.0, 1.0);
            const MediumFit fit;
            try {
                m = Material::from_medium(medium_from_appearance(albedo, mfp, ior, roughness, fit), fit);
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
        m.strength = float(strength);
        m.opaque = !translucent;
        return m;
    }

private:
    void warn(const std::string& what)
    {
        if (warnings_) warnings_->push_back(file_ + ": " + where_ + ": " + what);
    }

    const tinygltf::Value* extension(const tinygltf::Material& g, const char* name)
    {
        auto it = g.extensions.find(name);
        if (it == g.extensions.end()) return nullptr;
        if (!it->second.IsObject()) {
            warn(std::string(name) + " is not an object; ignored");
            return nullptr;
        }
        return &it->second;
    }

    double number(const std::string& what, const tinygltf::Value& v, double fallback)
    {
        if (v.IsNumber() && std::isfinite(v.GetNumberAsDouble())) return v.GetNumberAsDouble();
        warn(what + " is not a finite number; " + num(fallback) + " used");
        return fallback;
    }

    double positive(const std::string& what, const tinygltf::Value& v, double fallback)
    {
        const double x = number(what, v, fallback);
        if (x > 0) return x;
        warn(what + " " + num(x) + " is not positive; " + num(fallback) + " used");
        return fallback;
    }

    double clamped(const std::string& what, double x, double lo, double hi, double fallback)
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
    glm::dvec3 color(const std::string& what, const tinygltf::Value& ext, double lo)
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

    const std::string& file_;
    const tinygltf::Model& model_;
    std::vector<std::string>* warnings_;
    std::string where_;
};

/// The node's {"jade": {"deform": ...}} extras, fitted to the object's mesh.
std::optional<ProceduralDeformer> node_deformer(const std::string& file, const tinygltf::Node& node, int index,
                                                const TriangleMesh& mesh, std::vector<std::string>* warnings)
{
    if (!node.extras.Has("jade")) return std::nullopt;
    const tinygltf::Value& j = node.extras.Get("jade");
    auto warn = [&](const std::string& what) {
        if (warnings) warnings->push_back(file + ": node " + std::to_string(index) + ": " + what);
    };
    if (!j.IsObject() || !j.Has("deform")) return std::nullopt;
    const tinygltf::Value& d = j.Get("deform");
    if (!d.IsString()) {
        warn("extras.jade.deform is not a string; the node is static");
        return std::nullopt;
    }
    DeformerKind kind;
    try {
        kind = parse_deformer(d.Get<std::string>());
    } catch (const Error& e) {
        warn(std::string("extras.jade.deform: ") + e.what() + "; the node is static");
        return std::nullopt;
    }
    uint32_t axis = 1;
    if (j.Has("axis")) {
        const tinygltf::Value& a = j.Get("axis");
        if (a.IsNumber() && (a.GetNumberAsDouble() == 0 || a.GetNumberAsDouble() == 1 || a.GetNumberAsDouble() == 2))
            axis = uint32_t(a.GetNumberAsDouble());
        else warn("extras.jade.axis is not 0, 1 or 2; 1 (y) used");
    }
    return ProceduralDeformer::fit(kind, prepare_mesh(mesh), axis);
}

}  // namespace

Scene load_scene(const std::filesystem::path& path, std::vector<std::string>* warnings)
{
    const std::string name = io::display_name(path);
    return io::naming_file(name, [&] {
        const auto ext = io::lower_extension(path);
        if (ext != ".gltf" && ext != ".glb") io::fail(name, "a scene file must be .gltf or .glb, not '" + ext + "'");
        const std::string bytes = io::read_file(path);
        if (bytes.empty()) io::fail(name, "file is empty");
        const tinygltf::Model model = io::parse_gltf(path, name, bytes, ext == ".glb");
        Scene scene;
        scene.name = name;
        MaterialMapper mapper(name, model, warnings);
        std::vector<std::optional<Material>> materials(model.materials.size());
        std::optional<Material> no_material;
        for (io::GltfPrimitive& p : io::read_gltf_primitives(name, model)) {
            io::validate_loaded(p.mesh);
            if (p.material >= int(model.materials.size()))
                io::fail(name, "mesh " + std::to_string(p.mesh_index) + " primitive " + std::to_string(p.primitive) + ": material " +
                                   std::to_string(p.material) + " does not exist (" + std::to_string(model.materials.size()) +
                                   " materials)");
            auto& slot = p.material < 0 ? no_material : materials.at(size_t(p.material));
            if (!slot) slot = mapper.map(p.material);  // once per material: warnings once
            const auto& node = model.nodes[size_t(p.node)];
            SceneObject o;
            o.name = (node.name.empty() ? "node " + std::to_string(p.node) : node.name) + "/" + std::to_string(p.primitive);
            o.material = *slot;
            o.deformer = node_deformer(name, node, p.node, p.mesh, warnings);
            o.mesh = std::move(p.mesh);
            o.mesh.name = name + ": " + o.name;
            scene.objects.push_back(std::move(o));
        }
        if (scene.objects.empty()) io::fail(name, "the default scene has no triangle primitives");
        return scene;
    });
}

StaticBakeSource cached_bakes(const BakeCache& cache)
{
    StaticBakeSource s;
    s.lookup = [&cache](const PreparedMesh& mesh, const Material& material, const BakeSettings& settings) {
        const uint64_t key = bake_key(mesh, material, settings);
        return StaticBakeSource::Lookup{key, cache.load(key, mesh.vertex_count()).has_value()};
    };
    s.bake = [&cache](Context& context, const PreparedMesh& mesh, const Material& material, const BakeSettings& settings) {
        return bake_with_cache(context, cache, mesh, material, settings);
    };
    return s;
}

}  // namespace jade
