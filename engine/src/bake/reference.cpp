// bake/reference.cpp - the float64 CPU references of the bake (see jade/bake.hpp):
//   reference_ao  the GPU pass's rays (rays.hpp), intersected in double precision over a BVH
//                 traversed with the same stackless escape scheme as the shader;
//   reference_tm  brute-force vertex-disk rule over all pairs.
// Both run on all hardware threads; each vertex's result depends only on its own inputs, so
// the output does not depend on the thread count or schedule.
#include "bvh.hpp"
#include "disk_integral.hpp"
#include "rays.hpp"

#include <jade/dev/material.hpp>
#include <jade/bake.hpp>
#include <jade/error.hpp>
#include <jade/dev/reference.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <string>
#include <thread>

namespace jade {
namespace {

/// Calls body(k) for k in [0, n) on all hardware threads, in chunks of `chunk`.
template <class Body> void parallel_for(size_t n, size_t chunk, const Body& body)
{
    const size_t chunks = (n + chunk - 1) / chunk;
    const size_t threads = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), chunks);
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t b; (b = next.fetch_add(chunk)) < n;)
            for (size_t k = b, e = std::min(n, b + chunk); k < e; ++k) body(k);
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
}

/// The vertices to compute: `subset`, or all of them when it is empty. Validated.
std::vector<uint32_t> resolve_subset(const PreparedMesh& mesh, std::span<const uint32_t> subset, const char* where)
{
    const size_t n = mesh.vertex_count();
    if (subset.empty()) {
        std::vector<uint32_t> all(n);
        for (size_t i = 0; i < n; ++i) all[i] = uint32_t(i);
        return all;
    }
    for (uint32_t v : subset)
        if (v >= n)
            throw Error(std::string(where) + ": vertex " + std::to_string(v) + " out of range for " +
                        std::to_string(n) + " bake vertices");
    return {subset.begin(), subset.end()};
}

void check_ao_settings(const AoSettings& s, const char* where)
{
    const std::string w(where);
    if (s.rays == 0) throw Error(w + ": AoSettings.rays must be >= 1");
    if (!(std::isfinite(s.max_distance_rel) && s.max_distance_rel > 0.0f))
        throw Error(w + ": AoSettings.max_distance_rel = " + std::to_string(s.max_distance_rel) +
                    " must be finite and > 0");
    if (!(std::isfinite(s.ray_offset_rel) && s.ray_offset_rel >= 0.0f))
        throw Error(w + ": AoSettings.ray_offset_rel = " + std::to_string(s.ray_offset_rel) +
                    " must be finite and >= 0");
}

/// The mesh's triangles in BVH order (v0 and two edges, double) and the BVH over them.
struct TriangleScene {
    bake::Bvh bvh;
    std::vector<glm::dvec3> v0, e1, e2;
    double pad = 0.0;  ///< node boxes are widened by this much (mesh units) against rounding

    explicit TriangleScene(const PreparedMesh& mesh)
    {
        const size_t n = mesh.triangle_count();
        std::vector<glm::vec3> lo(n), hi(n);
        for (size_t t = 0; t < n; ++t) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                            c = mesh.positions[mesh.indices[3 * t + 2]];
            lo[t] = glm::min(a, glm::min(b, c));
            hi[t] = glm::max(a, glm::max(b, c));
        }
        bvh = bake::build_bvh(lo, hi, 4);
        v0.resize(n);
        e1.resize(n);
        e2.resize(n);
        for (size_t k = 0; k < n; ++k) {
            const size_t t = bvh.order[k];
            const glm::dvec3 a = mesh.positions[mesh.indices[3 * t]];
            v0[k] = a;
            e1[k] = glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]) - a;
            e2[k] = glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]]) - a;
        }
        pad = 1e-9 * double(mesh.diagonal);
    }

    /// Möller–Trumbore, no culling: the distance t of the hit, or 0 for a miss.
    double intersect(size_t k, const glm::dvec3& o, const glm::dvec3& d) const
    {
        const glm::dvec3 pvec = glm::cross(d, e2[k]);
        const double det = glm::dot(e1[k], pvec);
        if (std::abs(det) < 1e-300) return 0.0;
        const double inv = 1.0 / det;
        const glm::dvec3 tvec = o - v0[k];
        const double u = glm::dot(tvec, pvec) * inv;
        if (u < 0.0 || u > 1.0) return 0.0;
        const glm::dvec3 qvec = glm::cross(tvec, e1[k]);
        const double v = glm::dot(d, qvec) * inv;
        if (v < 0.0 || u + v > 1.0) return 0.0;
        return glm::dot(e2[k], qvec) * inv;
    }

    /// Slab test of a node's (padded) box against the segment o + t·d, t ∈ [0, t_max].
    bool overlaps(const bake::BvhNode& node, const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& inv,
                  double t_max) const
    {
        double t0 = 0.0, t1 = t_max;
        for (int a = 0; a < 3; ++a) {
            const double lo = double(node.lo[a]) - pad, hi = double(node.hi[a]) + pad;
            if (std::abs(d[a]) < 1e-300) {  // parallel to the slab
                if (o[a] < lo || o[a] > hi) return false;
                continue;
            }
            double ta = (lo - o[a]) * inv[a], tb = (hi - o[a]) * inv[a];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
            if (t0 > t1) return false;
        }
        return true;
    }

    /// Stackless pre-order traversal with escape pointers (d unit). `any`: stops at the first hit
    /// with 0 < t ≤ t_max and returns its t, or −1 for none; otherwise returns the nearest hit in
    /// (0, t_max), or t_max when there is none (the box tests shrink with it).
    double walk(const glm::dvec3& o, const glm::dvec3& d, double t_max, bool any) const
    {
        const glm::dvec3 inv(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);
        const uint32_t count = uint32_t(bvh.nodes.size());
        for (uint32_t i = 0; i < count;) {
            const bake::BvhNode& node = bvh.nodes[i];
            if (!overlaps(node, o, d, inv, t_max)) {
                i = node.escape;
                continue;
            }
            if (node.leaf()) {
                const uint32_t first = node.first();
                for (uint32_t k = first; k < first + bvh.counts[i]; ++k) {
                    const double t = intersect(k, o, d);
                    if (any && t > 0.0 && t <= t_max) return t;
                    if (!any && t > 0.0 && t < t_max) t_max = t;
                }
                i = node.escape;
            } else {
                ++i;
            }
        }
        return any ? -1.0 : t_max;
    }
    bool any_hit(const glm::dvec3& o, const glm::dvec3& d, double t_max) const
    {
        return walk(o, d, t_max, true) >= 0.0;
    }
    double nearest_hit(const glm::dvec3& o, const glm::dvec3& d, double t_max) const
    {
        return walk(o, d, t_max, false);
    }
};

void check_thickness_settings(const ThicknessSettings& s, const char* where)
{
    const std::string w(where);
    if (s.rays == 0 || s.rays > 1023) throw Error(w + ": ThicknessSettings.rays must be in 1..1023");
    if (!(s.cone_degrees > 0.0f && s.cone_degrees <= 90.0f))
        throw Error(w + ": ThicknessSettings.cone_degrees must be in (0, 90]");
    if (!(std::isfinite(s.max_distance_rel) && s.max_distance_rel > 0.0f))
        throw Error(w + ": ThicknessSettings.max_distance_rel must be finite and > 0");
    if (!(std::isfinite(s.ray_offset_rel) && s.ray_offset_rel >= 0.0f))
        throw Error(w + ": ThicknessSettings.ray_offset_rel must be >= 0");
}

double cos_cone(const ThicknessSettings& s) { return std::cos(double(s.cone_degrees) * std::numbers::pi / 180.0); }

}  // namespace

glm::vec3 ao_ray_direction(glm::vec3 normal, uint32_t vertex, uint32_t k, const AoSettings& settings)
{
    check_ao_settings(settings, "ao_ray_direction");
    if (k >= settings.rays)
        throw Error("ao_ray_direction: ray " + std::to_string(k) + " out of range for " +
                    std::to_string(settings.rays) + " rays");
    const bake::RaySample s =
        bake::ray_sample(bake::vertex_hashes(settings.seed, vertex), k, settings.rays, settings.low_discrepancy);
    return glm::vec3(bake::cosine_direction(glm::normalize(glm::dvec3(normal)), s.u1, s.u2));
}

namespace {

// What the ray references start from: the listed vertices (resolve_subset), the triangles, and
// the ray offset and reach converted to mesh units.
struct VertexRays {
    std::vector<uint32_t> list;
    TriangleScene scene;
    double eps, t_max;
};

VertexRays vertex_rays(const PreparedMesh& mesh, std::span<const uint32_t> vertices, float offset_rel, float max_rel,
                       const char* where)
{
    const double diagonal = double(mesh.diagonal);
    return {resolve_subset(mesh, vertices, where), TriangleScene(mesh), double(offset_rel) * diagonal,
            double(max_rel) * diagonal};
}

// Calls f(k, origin, normal, hashes) for the k-th listed vertex, in parallel: the unit normal, the
// ray origin offset by side · eps along it (+1: above the surface, −1: below it) and the
// vertex's ray hashes for `seed`.
template <class F>
void for_each_ray_origin(const PreparedMesh& mesh, const VertexRays& r, uint32_t seed, double side, F&& f)
{
    parallel_for(r.list.size(), 16, [&](size_t k) {
        const uint32_t v = r.list[k];
        const glm::dvec3 normal = glm::normalize(glm::dvec3(mesh.normals[v]));
        f(k, glm::dvec3(mesh.positions[v]) + side * r.eps * normal, normal, bake::vertex_hashes(seed, v));
    });
}

}  // namespace

std::vector<double> reference_thickness(const PreparedMesh& mesh, const ThicknessSettings& settings,
                                        std::span<const uint32_t> vertices)
{
    check_thickness_settings(settings, "reference_thickness");
    const VertexRays r =
        vertex_rays(mesh, vertices, settings.ray_offset_rel, settings.max_distance_rel, "reference_thickness");
    const double c = cos_cone(settings);
    std::vector<double> thickness(r.list.size());
    for_each_ray_origin(mesh, r, settings.seed, -1.0,
                        [&](size_t idx, glm::dvec3 origin, glm::dvec3 normal, const bake::VertexHashes& h) {
        double sum = 0.0;
        for (uint32_t k = 0; k < settings.rays; ++k) {
            const bake::RaySample s = bake::ray_sample(h, k, settings.rays, true);
            const glm::dvec3 d = bake::cone_direction(-normal, s.u1, s.u2, c);
            sum += std::min(r.scene.nearest_hit(origin, d, r.t_max) + r.eps / std::max(glm::dot(d, -normal), 0.05),
                            r.t_max);
        }
        thickness[idx] = sum / double(settings.rays);
    });
    return thickness;
}

std::vector<float> reference_ao(const PreparedMesh& mesh, const AoSettings& settings,
                                std::span<const uint32_t> vertices)
{
    check_ao_settings(settings, "reference_ao");
    const VertexRays r =
        vertex_rays(mesh, vertices, settings.ray_offset_rel, settings.max_distance_rel, "reference_ao");
    const uint32_t n = settings.rays;
    std::vector<float> ao(r.list.size());
    for_each_ray_origin(mesh, r, settings.seed, 1.0,
                        [&](size_t idx, glm::dvec3 origin, glm::dvec3 normal, const bake::VertexHashes& h) {
        uint32_t hits = 0;
        for (uint32_t k = 0; k < n; ++k) {
            const bake::RaySample s = bake::ray_sample(h, k, n, settings.low_discrepancy);
            hits += r.scene.any_hit(origin, bake::cosine_direction(normal, s.u1, s.u2), r.t_max) ? 1u : 0u;
        }
        ao[idx] = float(double(hits) / double(n));
    });
    return ao;
}

namespace {

// t_m and the normal sums N_c = ∫R_c(1 − A_o)·n dS per listed vertex, by brute force.
struct ReferenceSums {
    std::vector<uint32_t> vertices;  // the listed vertices (resolve_subset)
    std::vector<glm::dvec3> tm;
    std::vector<std::array<glm::dvec3, 3>> normal;
};

ReferenceSums reference_sums(const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                             std::span<const uint32_t> vertices, const char* where)
{
    const size_t m = mesh.vertex_count();
    if (ao.size() != m)
        throw Error(std::string(where) + ": " + std::to_string(ao.size()) + " AO values for " + std::to_string(m) +
                    " bake vertices");
    if (material.opaque)
        throw Error(std::string(where) + ": material '" + material.name + "' is opaque and has no t_m");
    const std::vector<uint32_t> list = resolve_subset(mesh, vertices, where);

    // Per vertex: position, area A_j (units²), weight 1 − A_o(j). Zero weights are dropped from
    // the neighbour list (they contribute exactly nothing).
    std::vector<glm::dvec3> pos(m);
    std::vector<double> weight(m);
    std::vector<uint32_t> sources;
    for (size_t j = 0; j < m; ++j) {
        if (!(ao[j] >= 0.0f && ao[j] <= 1.0f))
            throw Error(std::string(where) + ": AO of vertex " + std::to_string(j) + " = " + std::to_string(ao[j]) +
                        " is not in [0, 1]");
        pos[j] = glm::dvec3(mesh.positions[j]);
        weight[j] = 1.0 - double(ao[j]);
        if (weight[j] > 0.0 && mesh.areas[j] > 0.0f) sources.push_back(uint32_t(j));
    }
    const int channels = dev::is_grey(material) ? 1 : 3;
    const auto& profile = material.profile;

    ReferenceSums out{list, std::vector<glm::dvec3>(list.size()), std::vector<std::array<glm::dvec3, 3>>(list.size())};
    parallel_for(list.size(), 4, [&](size_t idx) {
        const uint32_t i = list[idx];
        double sum[3] = {0.0, 0.0, 0.0};
        const double rho_i = std::sqrt(double(mesh.areas[i]) / std::numbers::pi);
        std::array<glm::dvec3, 3> normal{};
        for (int c = 0; c < channels; ++c) {
            sum[c] = weight[i] * dev::profile_cdf(profile[c], rho_i);  // self disk
            normal[c] = sum[c] * glm::dvec3(mesh.normals[i]);
        }
        for (const uint32_t j : sources) {
            if (j == i) continue;
            const double r = glm::distance(pos[i], pos[j]);
            const double area = double(mesh.areas[j]);
            for (int c = 0; c < channels; ++c) {
                const double v = weight[j] * bake::vertex_disk_term(profile[c], r, area);
                sum[c] += v;
                normal[c] += v * glm::dvec3(mesh.normals[j]);
            }
        }
        out.tm[idx] = channels == 1 ? glm::dvec3(sum[0]) : glm::dvec3(sum[0], sum[1], sum[2]);
        if (channels == 1) normal[1] = normal[2] = normal[0];
        out.normal[idx] = normal;
    });
    return out;
}

}  // namespace

std::vector<glm::dvec3> reference_tm(const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                                     std::span<const uint32_t> vertices)
{
    return reference_sums(mesh, ao, material, vertices, "reference_tm").tm;
}

ReferenceScattering reference_scattering(const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                                         std::span<const uint32_t> vertices)
{
    const ReferenceSums sums = reference_sums(mesh, ao, material, vertices, "reference_scattering");
    const std::vector<uint32_t>& list = sums.vertices;
    ReferenceScattering out{std::vector<glm::dvec3>(list.size()), std::vector<glm::dvec3>(list.size())};
    for (size_t k = 0; k < list.size(); ++k) {
        const glm::dvec3 n = sums.normal[k][0] + sums.normal[k][1] + sums.normal[k][2];
        const double len = glm::length(n);
        out.normal[k] = len > 1e-300 ? n / len : glm::dvec3(mesh.normals[list[k]]);
        for (int c = 0; c < 3; ++c) {
            const double t = sums.tm[k][c];
            out.spread[k][c] = t > 0.0 ? std::clamp(1.0 - glm::length(sums.normal[k][c]) / t, 0.0, 1.0) : 0.0;
        }
    }
    return out;
}

}  // namespace jade
