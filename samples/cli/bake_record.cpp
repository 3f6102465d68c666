// bake_record.cpp - the JSON that `jade bake` stores with what it baked; see bake_record.hpp.
#include <jade/dev/names.hpp>
#include "bake_record.hpp"

#include <nlohmann/json.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <sstream>

namespace jade::cli::record {

namespace {

/// A number as JSON: every value written is finite (null would say "not measured").
std::string num(double v)
{
    if (!std::isfinite(v)) return "null";
    std::ostringstream os;
    os.precision(9);
    os << v;
    return os.str();
}

std::string profile(const ChannelProfile& p)
{
    std::ostringstream os;
    switch (p.kind) {
    case ProfileKind::Burley: os << "{\"kind\":\"burley\",\"d\":" << num(p.d) << "}"; break;
    case ProfileKind::Dipole:
        os << "{\"kind\":\"dipole\",\"sigma_tr\":" << num(p.sigma_tr) << ",\"z_r\":" << num(p.z_r)
           << ",\"z_v\":" << num(p.z_v) << "}";
        break;
    case ProfileKind::Gaussians:
        os << "{\"kind\":\"gaussians\",\"weights\":[";
        for (uint32_t k = 0; k < p.gaussian_count; ++k) os << (k ? "," : "") << num(p.weight[k]);
        os << "],\"variances\":[";
        for (uint32_t k = 0; k < p.gaussian_count; ++k) os << (k ? "," : "") << num(p.variance[k]);
        os << "]}";
        break;
    }
    return os.str();
}

}  // namespace

std::string quoted(const std::string& text)
{
    return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string units()
{
    return "\"units\":\"t_m unitless (profile normalised to 1 over the plane); AO in [0,1]; thickness and profile "
           "lengths in mesh units\"";
}

std::string material(const Material& m)
{
    std::ostringstream os;
    os << "{\"name\":" << quoted(m.name) << ",\"albedo\":[" << num(m.albedo.x) << "," << num(m.albedo.y) << ","
       << num(m.albedo.z) << "],\"strength\":" << num(m.strength) << ",\"ior\":" << num(m.ior)
       << ",\"roughness\":" << num(m.roughness) << ",\"transmission\":" << (m.transmission.enabled() ? "true" : "false")
       << ",\"profiles\":[" << profile(m.profile[0]) << "," << profile(m.profile[1]) << "," << profile(m.profile[2])
       << "]}";
    return os.str();
}

std::string settings(const BakeSettings& s, const BakeResult& r)
{
    std::ostringstream os;
    os << "{\"ao_rays\":" << s.ao.rays << ",\"ao_low_discrepancy\":" << (s.ao.low_discrepancy ? "true" : "false")
       << ",\"ao_seed\":" << s.ao.seed << ",\"ao_max_distance_rel\":" << num(s.ao.max_distance_rel)
       << ",\"ao_epsilon_rel\":" << num(s.ao.ray_offset_rel) << ",\"tm_method\":\""
       << dev::tm_method_name(r.method_used) << "\",\"tm_epsilon\":" << num(s.tm_opening_ratio)
       << ",\"tm_grid_resolution\":" << num(s.tm_grid_resolution)
       << ",\"thickness_rays\":" << (r.thickness.empty() ? 0 : s.thickness.rays) << "}";
    return os.str();
}

std::string timings(const BakeResult& r)
{
    std::ostringstream os;
    os << "{\"wall\":" << num(r.timings.wall_ms) << ",\"gpu\":" << num(r.timings.gpu_total_ms);
    for (auto& [stage, ms] : r.timings.gpu_stages) os << "," << quoted(stage) << ":" << num(ms);
    os << "}";
    return os.str();
}

}  // namespace jade::cli::record

namespace jade::cli {

double diagonal(const TriangleMesh& mesh)
{
    if (mesh.positions.empty()) return 0.0;
    glm::dvec3 lo(mesh.positions[0]), hi(mesh.positions[0]);
    for (const auto& p : mesh.positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    return glm::length(hi - lo);
}

BakeResult bake_at_unit_scale(Baker& baker, const TriangleMesh& mesh, const Material& material,
                              const BakeSettings& settings, PreparedMesh& prepared)
{
    const double d = diagonal(mesh);
    const int k = d > 0.0 && std::isfinite(d) ? -int(std::lround(std::log2(d))) : 0;
    if (k == 0) {
        prepared = prepare_mesh(mesh);
        return baker.bake(prepared, material, settings);
    }
    TriangleMesh scaled = mesh;
    for (auto& p : scaled.positions) p = glm::vec3(std::ldexp(p.x, k), std::ldexp(p.y, k), std::ldexp(p.z, k));
    prepared = prepare_mesh(scaled);
    BakeResult r = baker.bake(prepared, material.scaled(std::ldexp(1.0, k)), settings);
    for (auto& t : r.thickness) t = std::ldexp(t, -k);
    return r;
}

}  // namespace jade::cli
