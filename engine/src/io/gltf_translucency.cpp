// io/gltf_translucency.cpp - JADE_materials_translucency: see gltf_translucency.hpp.
#include "io/gltf_translucency.hpp"

#include "io/common.hpp"

#include <cfloat>
#include <cmath>
#include <cstdio>

namespace jade::io {

namespace {

using ordered = nlohmann::ordered_json;

std::string fmt(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

const char* kind_name(ProfileKind k)
{
    return k == ProfileKind::Burley ? "burley" : k == ProfileKind::Dipole ? "dipole" : "gaussians";
}

ordered vec3(glm::vec3 v) { return ordered::array({double(v.x), double(v.y), double(v.z)}); }

ordered profile(const ChannelProfile& p)
{
    ordered j = {{"kind", kind_name(p.kind)}};
    if (p.kind == ProfileKind::Burley) j["d"] = p.d;
    if (p.kind == ProfileKind::Dipole)
        j["sigmaTr"] = p.sigma_tr, j["zR"] = p.z_r, j["zV"] = p.z_v, j["total"] = p.dipole_total;
    if (p.kind == ProfileKind::Gaussians) {
        j["weights"] = ordered::array(), j["variances"] = ordered::array();
        for (uint32_t k = 0; k < p.gaussian_count; ++k)
            j["weights"].push_back(p.weight[k]), j["variances"].push_back(p.variance[k]);
    }
    return j;
}

/// Reads the checked values of one extension object, naming what it reads in its messages.
class Reader {
public:
    Reader(const std::string& file, const std::string& where) : file_(file), where_(where) {}

    [[noreturn]] void bad(const std::string& property, const std::string& what) const
    {
        fail(file_, where_ + ": " + kTranslucencyExtension + "." + property + " " + what);
    }

    const nlohmann::json& member(const nlohmann::json& j, const std::string& path, const char* key) const
    {
        const std::string property = path.empty() ? key : path + "." + key;
        if (!j.is_object()) bad(path, "is not a JSON object");
        const auto it = j.find(key);
        if (it == j.end()) bad(property, "is missing");
        return *it;
    }

    /// A number in [lo, hi] (open at either end when `open`), representable as a float when `as_float`.
    double number(const nlohmann::json& j, const std::string& property, double lo, double hi, bool open_lo = false,
                  bool as_float = true) const
    {
        if (!j.is_number()) bad(property, "is not a number");
        const double v = j.get<double>();
        const double top = as_float ? std::min(hi, double(FLT_MAX)) : hi;
        if (!std::isfinite(v) || v < lo || (open_lo && v == lo) || v > top)
            bad(property, "= " + j.dump() + " is not in " + (open_lo ? "(" : "[") + fmt(lo) + ", " + fmt(top) + "]");
        return v;
    }

    double get(const nlohmann::json& obj, const std::string& path, const char* key, double lo, double hi,
               bool open_lo = false, bool as_float = true) const
    {
        return number(member(obj, path, key), path.empty() ? key : path + "." + key, lo, hi, open_lo, as_float);
    }

    glm::vec3 get3(const nlohmann::json& obj, const std::string& path, const char* key, double lo, double hi) const
    {
        const std::string property = path.empty() ? key : path + "." + key;
        const auto& a = member(obj, path, key);
        if (!a.is_array() || a.size() != 3) bad(property, "is not an array of 3 numbers");
        glm::vec3 v;
        for (int c = 0; c < 3; ++c)
            v[c] = float(number(a[size_t(c)], property + "[" + std::to_string(c) + "]", lo, hi));
        return v;
    }

    ChannelProfile channel(const nlohmann::json& j, int c) const
    {
        const std::string path = "profiles[" + std::to_string(c) + "]";
        const auto& kind = member(j, path, "kind");
        ChannelProfile p;
        constexpr double kBig = 1e300;  // profile parameters are doubles: any finite positive length
        if (kind == "burley") {
            p.kind = ProfileKind::Burley;
            p.d = get(j, path, "d", 0.0, kBig, true, false);
        } else if (kind == "dipole") {
            p.kind = ProfileKind::Dipole;
            p.sigma_tr = get(j, path, "sigmaTr", 0.0, kBig, false, false);
            p.z_r = get(j, path, "zR", 0.0, kBig, true, false);
            p.z_v = get(j, path, "zV", 0.0, kBig, true, false);
            p.dipole_total = get(j, path, "total", 0.0, 1.0, true, false);
        } else if (kind == "gaussians") {
            p.kind = ProfileKind::Gaussians;
            const auto& w = member(j, path, "weights");
            const auto& v = member(j, path, "variances");
            if (!w.is_array() || !v.is_array() || w.empty() || w.size() != v.size() ||
                w.size() > size_t(ChannelProfile::kMaxGaussians))
                bad(path, "needs 1 to 6 weights and as many variances");
            double sum = 0.0;
            for (size_t k = 0; k < w.size(); ++k) {
                p.weight[k] = number(w[k], path + ".weights[" + std::to_string(k) + "]", 0.0, 1.0, false, false);
                p.variance[k] = number(v[k], path + ".variances[" + std::to_string(k) + "]", 0.0, kBig, true, false);
                sum += p.weight[k];
            }
            // Written normalised; a sum off by more than rounding is not a profile of Jade's.
            if (!(std::abs(sum - 1.0) <= 1e-9)) bad(path + ".weights", "sum to " + fmt(sum) + ", not 1");
            p.gaussian_count = uint32_t(w.size());
        } else {
            bad(path + ".kind", "= " + kind.dump() + " is not one of \"burley\", \"dipole\", \"gaussians\"");
        }
        return p;
    }

private:
    const std::string& file_;
    const std::string& where_;
};

}  // namespace

nlohmann::ordered_json translucency_extension(const std::string& file, const Material& m)
{
    const Transmission& t = m.transmission;
    ordered ext = {{"name", m.name},
                   {"albedo", vec3(m.albedo)},
                   {"strength", double(m.strength)},
                   {"spreadStrength", double(m.spread_strength)},
                   {"ior", double(m.ior)},
                   {"roughness", double(m.roughness)},
                   {"specular", double(m.specular)},
                   {"boundaryTransmittance", m.boundary_transmittance},
                   {"transmission",
                    {{"sigmaT", vec3(t.sigma_t)},
                     {"sigmaSReduced", vec3(t.sigma_s_reduced)},
                     {"sigmaTr", vec3(t.sigma_tr)},
                     {"sourceDepth", vec3(t.source_depth)},
                     {"extrapolation", vec3(t.extrapolation)},
                     {"weight", double(t.weight)},
                     {"diffusionWeight", double(t.diffusion_weight)},
                     {"lobe", double(t.lobe)},
                     {"normalMix", double(t.normal_mix)}}},
                   {"profiles", ordered::array({profile(m.profile[0]), profile(m.profile[1]), profile(m.profile[2])})}};
    // The reader's own checks, so that nothing is written that Jade would refuse to read back.
    try {
        material_from_translucency(file, "material " + m.name, nlohmann::json::parse(ext.dump()));
    } catch (const Error& e) {
        fail(file, std::string("cannot write the material: ") + e.what());
    }
    return ext;
}

Material material_from_translucency(const std::string& file, const std::string& where, const nlohmann::json& ext)
{
    const Reader r(file, where);
    Material m;
    if (!ext.is_object()) r.bad("", "is not a JSON object");
    if (ext.contains("name")) {
        if (!ext["name"].is_string()) r.bad("name", "is not a string");
        m.name = ext["name"].get<std::string>();
    } else {
        m.name = where;
    }
    constexpr double kMaxStrength = 1e6;  // the command line's bound on --strength
    m.albedo = r.get3(ext, "", "albedo", 0.0, 1.0);
    m.strength = float(r.get(ext, "", "strength", 0.0, kMaxStrength));
    m.spread_strength = float(r.get(ext, "", "spreadStrength", 0.0, kMaxStrength));
    m.ior = float(r.get(ext, "", "ior", 0.2, 5.0, true));
    m.roughness = float(r.get(ext, "", "roughness", 0.0, 1.0));
    m.specular = float(r.get(ext, "", "specular", 0.0, kMaxStrength));
    const auto& boundary = r.member(ext, "", "boundaryTransmittance");
    if (!boundary.is_boolean()) r.bad("boundaryTransmittance", "is not true or false");
    m.boundary_transmittance = boundary.get<bool>();
    const auto& t = r.member(ext, "", "transmission");
    const std::string tp = "transmission";
    m.transmission.sigma_t = r.get3(t, tp, "sigmaT", 0.0, FLT_MAX);
    m.transmission.sigma_s_reduced = r.get3(t, tp, "sigmaSReduced", 0.0, FLT_MAX);
    m.transmission.sigma_tr = r.get3(t, tp, "sigmaTr", 0.0, FLT_MAX);
    m.transmission.source_depth = r.get3(t, tp, "sourceDepth", 0.0, FLT_MAX);
    m.transmission.extrapolation = r.get3(t, tp, "extrapolation", 0.0, FLT_MAX);
    m.transmission.weight = float(r.get(t, tp, "weight", 0.0, kMaxStrength));
    m.transmission.diffusion_weight = float(r.get(t, tp, "diffusionWeight", 0.0, kMaxStrength));
    m.transmission.lobe = float(r.get(t, tp, "lobe", 0.0, 1e4));
    m.transmission.normal_mix = float(r.get(t, tp, "normalMix", 0.0, 1.0));
    const auto& profiles = r.member(ext, "", "profiles");
    if (!profiles.is_array() || profiles.size() != 3) r.bad("profiles", "is not an array of 3 profiles (R, G, B)");
    for (int c = 0; c < 3; ++c) m.profile[size_t(c)] = r.channel(profiles[size_t(c)], c);
    return m;
}

nlohmann::json to_json(const tinygltf::Value& v)
{
    switch (v.Type()) {
    case tinygltf::BOOL_TYPE: return v.Get<bool>();
    case tinygltf::INT_TYPE: return v.Get<int>();
    case tinygltf::REAL_TYPE: return v.Get<double>();
    case tinygltf::STRING_TYPE: return v.Get<std::string>();
    case tinygltf::ARRAY_TYPE: {
        nlohmann::json a = nlohmann::json::array();
        for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(to_json(v.Get(int(i))));
        return a;
    }
    case tinygltf::OBJECT_TYPE: {
        nlohmann::json o = nlohmann::json::object();
        for (const auto& key : v.Keys()) o[key] = to_json(v.Get(key));
        return o;
    }
    default: return nullptr;
    }
}

}  // namespace jade::io
