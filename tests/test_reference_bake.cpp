// The float64 bake references (engine/src/bake/{bvh,reference}.cpp, rays.hpp,
// disk_integral.hpp): BVH structure, the ray set, reference_ao against analytic occlusion,
// reference_tm against the exact limits of the vertex-disk rule, and speed on the bunny.
#include "../engine/src/bake/bvh.hpp"
#include "../engine/src/bake/disk_integral.hpp"
#include "../engine/src/bake/rays.hpp"

#include "test_support.hpp"

#include <jade/dev/material.hpp>
#include <jade/bake.hpp>
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/dev/reference.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <utility>

using namespace jade;

namespace {

constexpr double kPi = std::numbers::pi;

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

uint32_t nearest_vertex(const PreparedMesh& m, glm::vec3 p)
{
    uint32_t best = 0;
    for (uint32_t v = 1; v < m.vertex_count(); ++v)
        if (glm::distance(m.positions[v], p) < glm::distance(m.positions[best], p)) best = v;
    return best;
}

/// a and b in one mesh (b's indices offset).
TriangleMesh merged(TriangleMesh a, const TriangleMesh& b)
{
    const uint32_t base = uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    a.normals.clear();
    for (uint32_t i : b.indices) a.indices.push_back(base + i);
    return a;
}

TriangleMesh translated(TriangleMesh m, glm::vec3 offset)
{
    for (auto& p : m.positions) p += offset;
    return m;
}

TriangleMesh scaled(TriangleMesh m, float f)
{
    for (auto& p : m.positions) p *= f;
    return m;
}

/// A deterministic AO pattern in [0, 0.9] with exact zeros and repeats.
std::vector<float> ao_pattern(size_t n)
{
    std::vector<float> ao(n);
    for (size_t j = 0; j < n; ++j) ao[j] = float(j % 10) * 0.1f;
    return ao;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// BVH

TEST(Bvh, StructureOrderAndEscapePointers)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f), s(0.0f, 0.5f);
    for (const bake::BvhSplit split : {bake::BvhSplit::Median, bake::BvhSplit::Sah})
        for (uint32_t n : {0u, 1u, 2u, 5u, 64u, 1000u, 1001u}) {
            for (uint32_t leaf : {1u, 4u, 7u}) {
                const bool median = split == bake::BvhSplit::Median;
                std::vector<glm::vec3> lo(n), hi(n);
                for (uint32_t i = 0; i < n; ++i) {
                    lo[i] = {u(rng), u(rng), (i % 3 == 0) ? 1.0f : u(rng)};  // some coincident coordinates
                    hi[i] = lo[i] + glm::vec3(s(rng), s(rng), s(rng));
                }
                const bake::Bvh bvh = bake::build_bvh(lo, hi, leaf, split);
                SCOPED_TRACE("n = " + std::to_string(n) + ", leaf_size = " + std::to_string(leaf) +
                             (median ? ", median" : ", SAH"));
                ASSERT_EQ(bvh.nodes.size(), bvh.counts.size());
                ASSERT_EQ(bvh.order.size(), n);
                if (n == 0) {
                    EXPECT_TRUE(bvh.nodes.empty());
                    EXPECT_EQ(bvh.depth, 0u);
                    continue;
                }
                std::vector<uint32_t> sorted = bvh.order;
                std::sort(sorted.begin(), sorted.end());
                for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i) << "order is not a permutation";
                const uint32_t count = uint32_t(bvh.nodes.size());
                EXPECT_EQ(bvh.nodes[0].escape, count);
                EXPECT_EQ(bvh.counts[0], n);
                if (median)
                    EXPECT_LE(bvh.depth, uint32_t(std::ceil(std::log2(std::max(1.0, double(n) / leaf)))) + 1);
                else
                    EXPECT_LE(bvh.depth, 48u + uint32_t(std::ceil(std::log2(std::max(1.0, double(n))))));

                std::vector<int> seen(n, 0);
                for (uint32_t i = 0; i < count; ++i) {
                    const bake::BvhNode& node = bvh.nodes[i];
                    const uint32_t first = node.first(), c = bvh.counts[i];
                    ASSERT_LE(first + c, n);
                    ASSERT_GE(c, 1u);
                    glm::vec3 ulo = lo[bvh.order[first]], uhi = hi[bvh.order[first]];
                    for (uint32_t k = first; k < first + c; ++k) {
                        ulo = glm::min(ulo, lo[bvh.order[k]]);
                        uhi = glm::max(uhi, hi[bvh.order[k]]);
                    }
                    EXPECT_EQ(node.lo, ulo) << "node " << i << " bounds are not the union of its range";
                    EXPECT_EQ(node.hi, uhi) << "node " << i;
                    ASSERT_GT(node.escape, i);
                    ASSERT_LE(node.escape, count);
                    if (node.leaf()) {
                        EXPECT_LE(c, leaf);
                        EXPECT_EQ(node.leaf_count(), c) << "leaf count packed in the range";
                        EXPECT_EQ(node.escape, i + 1);
                        for (uint32_t k = first; k < first + c; ++k) ++seen[bvh.order[k]];
                    } else {
                        EXPECT_GT(c, leaf);
                        const uint32_t a = i + 1, b = bvh.nodes[a].escape;  // the two children
                        ASSERT_LT(b, count);
                        EXPECT_EQ(bvh.nodes[a].first(), first);
                        EXPECT_EQ(bvh.nodes[b].first(), first + bvh.counts[a]);
                        EXPECT_EQ(bvh.counts[a] + bvh.counts[b], c);
                        if (median) EXPECT_LE(bvh.counts[b] - bvh.counts[a], 1u) << "median split";
                        EXPECT_EQ(bvh.nodes[b].escape, node.escape);
                    }
                }
                for (uint32_t p = 0; p < n; ++p)
                    ASSERT_EQ(seen[p], 1) << "primitive " << p << " not in exactly one leaf";

                // Stackless traversal that skips random subtrees visits exactly the leaves a
                // recursive traversal with the same decisions visits.
                auto skip = [](uint32_t i) { return bake::pcg_hash(i) % 5 == 0; };
                std::vector<uint32_t> stackless, recursive;
                for (uint32_t i = 0; i < count;) {
                    const bool leaf_node = bvh.nodes[i].leaf();
                    if (!skip(i) && leaf_node) stackless.push_back(i);
                    i = (skip(i) || leaf_node) ? bvh.nodes[i].escape : i + 1;
                }
                std::function<void(uint32_t)> visit = [&](uint32_t i) {
                    if (skip(i)) return;
                    if (bvh.nodes[i].leaf()) return recursive.push_back(i);
                    visit(i + 1);
                    visit(bvh.nodes[i + 1].escape);
                };
                visit(0);
                EXPECT_EQ(stackless, recursive);
            }
        }
}

namespace {

/// The SAH cost of a tree in units of one traversal step (a node or a primitive, as in the AO
/// shader): Σ over nodes of P(visit) · (1 + primitives if a leaf), P = area / root area.
double sah_cost(const bake::Bvh& bvh)
{
    auto area = [](const bake::BvhNode& n) {
        const glm::vec3 e = n.hi - n.lo;
        return double(e.x) * e.y + double(e.y) * e.z + double(e.z) * e.x;
    };
    double cost = 0;
    for (size_t i = 0; i < bvh.nodes.size(); ++i)
        cost += area(bvh.nodes[i]) / area(bvh.nodes[0]) * (1.0 + (bvh.nodes[i].leaf() ? bvh.counts[i] : 0));
    return cost;
}

}  // namespace

TEST(Bvh, SahTreeIsCheaperThanMedianTreeOnTheBunny)
{
    // The AO tree is built with BvhSplit::Sah: its expected traversal cost must be clearly
    // below the median split's (on the bunny's AO rays: 10 % fewer steps per ray, 11 % fewer
    // loop iterations per 8-lane group).
    const PreparedMesh p = prepare_mesh(load_mesh(test::asset("bunny00.off")));
    std::vector<glm::vec3> lo(p.triangle_count()), hi(p.triangle_count());
    for (size_t t = 0; t < p.triangle_count(); ++t) {
        const glm::vec3 a = p.positions[p.indices[3 * t]], b = p.positions[p.indices[3 * t + 1]],
                        c = p.positions[p.indices[3 * t + 2]];
        lo[t] = glm::min(a, glm::min(b, c));
        hi[t] = glm::max(a, glm::max(b, c));
    }
    const double median = sah_cost(bake::build_bvh(lo, hi, 4, bake::BvhSplit::Median));
    const double sah = sah_cost(bake::build_bvh(lo, hi, 4, bake::BvhSplit::Sah));
    std::printf("SAH cost: median split %.1f, binned SAH %.1f (%.1f %% lower)\n", median, sah,
                100.0 * (1.0 - sah / median));
    EXPECT_LT(sah, 0.9 * median);
}

// ---------------------------------------------------------------------------------------------
// Ray set

TEST(Rays, GoldenValues)
{
    // Independent evaluation (Python) of the spec in rays.hpp.
    EXPECT_EQ(bake::pcg_hash(0), 129708002u);
    EXPECT_EQ(bake::pcg_hash(1), 2831084092u);
    EXPECT_EQ(bake::pcg_hash(12345), 4099845390u);
    EXPECT_EQ(bake::pcg_hash(0xffffffffu), 3861530882u);
    const bake::VertexHashes h = bake::vertex_hashes(1, 7);
    EXPECT_EQ(h.h0, 2809854175u);
    EXPECT_EQ(h.h1, 1774872857u);
    auto fixed = [](float u) { return uint32_t(double(u) * 16777216.0); };
    bake::RaySample s = bake::ray_sample(h, 5, 64, true);
    EXPECT_EQ(fixed(s.u1), 12286712u);
    EXPECT_EQ(fixed(s.u2), 641641u);
    s = bake::ray_sample(h, 37, 100, true);
    EXPECT_EQ(fixed(s.u1), 406345u);
    EXPECT_EQ(fixed(s.u2), 903785u);
    s = bake::ray_sample(h, 5, 64, false);
    EXPECT_EQ(fixed(s.u1), 12919476u);
    EXPECT_EQ(fixed(s.u2), 9852223u);
    EXPECT_EQ(bake::bit_reverse(1u), 0x80000000u);
    EXPECT_EQ(bake::bit_reverse(0x12345678u), 0x1E6A2C48u);
}

TEST(Rays, StratifiedCosineWeightedUnitDirections)
{
    const AoSettings settings{.rays = 1000};
    const glm::vec3 normals[] = {{0, 0, 1}, {0, 0, -1}, glm::normalize(glm::vec3(1, -2, 0.3f)), {1, 0, 0}};
    for (const glm::vec3 n : normals) {
        std::vector<double> u1;
        double mean_cos = 0.0;
        for (uint32_t k = 0; k < settings.rays; ++k) {
            const glm::vec3 d = ao_ray_direction(n, 42, k, settings);
            EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
            const double c = glm::dot(glm::dvec3(d), glm::dvec3(n));
            EXPECT_GE(c, -1e-7);
            mean_cos += c / settings.rays;
            u1.push_back(1.0 - c * c);  // u1 = sin²θ
        }
        EXPECT_NEAR(mean_cos, 2.0 / 3.0, 1e-3);  // E[cos θ] of the cosine distribution
        // Rotated Hammersley: one u1 per stratum of width 1/N (cyclically).
        std::sort(u1.begin(), u1.end());
        for (size_t k = 1; k < u1.size(); ++k) EXPECT_NEAR(u1[k] - u1[k - 1], 1e-3, 2e-6) << k;
    }
    EXPECT_EQ(ao_ray_direction({0, 0, 1}, 3, 9, settings), ao_ray_direction({0, 0, 1}, 3, 9, settings));
    EXPECT_NE(ao_ray_direction({0, 0, 1}, 3, 9, settings), ao_ray_direction({0, 0, 1}, 4, 9, settings));
    EXPECT_THROW(ao_ray_direction({0, 0, 1}, 3, 1000, settings), Error);
}

// ---------------------------------------------------------------------------------------------
// reference_ao

TEST(ReferenceAo, OpenSurfacesAreUnoccluded)
{
    TriangleMesh tri;
    tri.name = "triangle";
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.indices = {0, 1, 2};
    for (const auto& ao : reference_ao(prepare_mesh(tri), AoSettings{.rays = 256, .max_distance_rel = 10.0f}))
        EXPECT_EQ(ao, 0.0f);
    const PreparedMesh plane = prepare_mesh(dev::procedural::grid(16, 0.25f));
    for (bool ld : {true, false})
        for (const auto& ao :
             reference_ao(plane, AoSettings{.rays = 128, .low_discrepancy = ld, .max_distance_rel = 2.0f}))
            EXPECT_EQ(ao, 0.0f);
}

TEST(ReferenceAo, InsideClosedBoxEveryRayHits)
{
    TriangleMesh box = dev::procedural::box({-1, -1, -1}, {1, 1, 1}, 4);
    for (size_t t = 0; t < box.indices.size(); t += 3) std::swap(box.indices[t + 1], box.indices[t + 2]);  // inward
    const PreparedMesh m = prepare_mesh(box);
    const uint32_t floor_centre = nearest_vertex(m, {0, 0, -1});
    ASSERT_NEAR(m.normals[floor_centre].z, 1.0f, 1e-6f);
    for (bool ld : {true, false}) {
        const AoSettings s{.rays = 1024, .low_discrepancy = ld, .max_distance_rel = 1.0f};  // reach = the diagonal
        EXPECT_EQ(reference_ao(m, s, std::vector<uint32_t>{floor_centre})[0], 1.0f);
    }
    // With a reach shorter than the nearest wall nothing is hit.
    EXPECT_EQ(
        reference_ao(m, AoSettings{.rays = 256, .max_distance_rel = 0.25f}, std::vector<uint32_t>{floor_centre})[0],
        0.0f);
}

TEST(ReferenceAo, ParallelPlaneMatchesAnalyticFraction)
{
    // Grid at z = 0 under a parallel plane at z = h. A cosine ray leaving at polar angle θ
    // reaches the plane at distance (h − ε)/cos θ, so A_o = P(cos θ ≥ (h − ε)/L) = 1 − ((h − ε)/L)².
    const float h = 1.0f;
    const PreparedMesh m =
        prepare_mesh(merged(dev::procedural::grid(10, 1.0f), translated(dev::procedural::grid(10, 1.0f), {0, 0, h})));
    const uint32_t centre = nearest_vertex(m, {0, 0, 0});
    for (float rel : {0.08f, 0.1f, 0.2f}) {
        const double L = double(rel) * m.diagonal, eps = 1e-4 * double(m.diagonal);
        const double expected = std::max(0.0, 1.0 - std::pow((h - eps) / L, 2.0));
        for (bool ld : {true, false}) {
            const AoSettings s{
                .rays = 4096, .low_discrepancy = ld, .seed = 3, .max_distance_rel = rel, .ray_offset_rel = 1e-4f};
            const float ao = reference_ao(m, s, std::vector<uint32_t>{centre})[0];
            // Low discrepancy: the hit set depends on u1 alone, stratified in 1/N. i.i.d.: 4σ.
            const double tol = ld ? 2.0 / 4096 : 4.0 * std::sqrt(expected * (1 - expected) / 4096) + 1e-9;
            EXPECT_NEAR(ao, expected, tol) << "max_distance_rel " << rel << (ld ? " LD" : " iid");
        }
    }
}

TEST(ReferenceAo, SubsetsDeterminismAndErrors)
{
    const PreparedMesh m = prepare_mesh(procedural::sphere(1.0f, 24, 48));
    const AoSettings s{.rays = 64, .max_distance_rel = 0.5f};
    // A convex surface: rays leave it. Inside-out it occludes itself.
    for (float ao : reference_ao(m, s)) EXPECT_EQ(ao, 0.0f);
    TriangleMesh bowl = dev::procedural::box({-1, -1, 0}, {1, 1, 0.5f}, 6);
    bowl = merged(bowl, translated(dev::procedural::grid(6, 0.5f), {0, 0, 1.0f}));
    const PreparedMesh b = prepare_mesh(bowl);
    const std::vector<float> all = reference_ao(b, s);
    const std::vector<uint32_t> subset = {5, 0, 17, uint32_t(b.vertex_count() - 1), 17};
    const std::vector<float> some = reference_ao(b, s, subset);
    ASSERT_EQ(some.size(), subset.size());
    for (size_t k = 0; k < subset.size(); ++k) EXPECT_EQ(some[k], all[subset[k]]);
    EXPECT_EQ(reference_ao(b, s), all);
    EXPECT_GT(*std::max_element(all.begin(), all.end()), 0.2f);  // the top of the box sees the plate
    EXPECT_THROW(reference_ao(b, s, std::vector<uint32_t>{uint32_t(b.vertex_count())}), Error);
    EXPECT_THROW(reference_ao(b, AoSettings{.rays = 0}), Error);
    EXPECT_THROW(reference_ao(b, AoSettings{.max_distance_rel = -1.0f}), Error);
}

// ---------------------------------------------------------------------------------------------
// The vertex-disk integral

namespace {

/// The t-formula of disk_integral converged adaptively.
double disk_adaptive(const ChannelProfile& p, double r, double rho)
{
    if (r == 0.0) return dev::profile_cdf(p, rho);
    auto g = [&](double t) {
        const double c = std::clamp((t * t + r * r - rho * rho) / (2 * t * r), -1.0, 1.0);
        return bake::radial_density(p, t) * std::acos(c) / kPi;
    };
    return dev::profile_cdf(p, std::max(rho - r, 0.0)) + bake::integrate(g, std::abs(r - rho), r + rho, 1e-12, 1e-300);
}

/// The disk integral in polar coordinates about x: along direction ψ the disk spans the
/// distances [T1, T2], holding a fraction (cdf(T2) − cdf(T1)) / 2π of the profile.
double disk_polar(const ChannelProfile& p, double r, double rho)
{
    auto g = [&](double psi) {
        const double c = r * std::cos(psi),
                     root = std::sqrt(std::max(0.0, rho * rho - r * r * std::sin(psi) * std::sin(psi)));
        return (dev::profile_cdf(p, std::max(c + root, 0.0)) - dev::profile_cdf(p, std::max(c - root, 0.0))) /
               kPi;  // ψ and −ψ
    };
    return bake::integrate(g, 0.0, r <= rho ? kPi : std::asin(rho / r), 1e-12, 1e-300);
}

}  // namespace

TEST(DiskIntegral, DistanceFormulaIsTheDiskIntegral)
{
    const double w[2] = {0.4, 0.6}, v[2] = {0.05, 0.6};
    for (const auto& p :
         {ChannelProfile::burley(0.3), ChannelProfile::dipole(1.0, 0.1, 1.3), ChannelProfile::gaussians(w, v)})
        for (double rho : {0.1, 1.0})
            for (double f : {0.0, 0.3, 0.99, 1.0, 1.01, 1.5, 3.99}) {
                const double a = disk_adaptive(p, f * rho, rho), b = disk_polar(p, f * rho, rho);
                EXPECT_NEAR(a, b, 1e-9 * b) << "r/ρ = " << f << " ρ = " << rho;
            }
}

TEST(DiskIntegral, GaussLegendreAccuracyAndFarFieldSwitch)
{
    // Worst relative error of the 8-point rule over r ∈ [0, 4ρ), and the jump of the
    // vertex-disk rule where it switches to A·R(r) at r = 4ρ, against ρ / (profile length).
    const double w[1] = {1.0}, v[1] = {1.0};
    const std::pair<const char*, ChannelProfile> kinds[] = {{"burley d=1", ChannelProfile::burley(1.0)},
                                                            {"dipole z_r=0.9", ChannelProfile::dipole(1.0, 0.1, 1.3)},
                                                            {"gaussian σ=1", ChannelProfile::gaussians(w, v)}};
    for (const auto& [name, p] : kinds)
        for (double rho : {0.1, 0.25, 0.5, 1.0, 2.0}) {
            double worst = 0.0;
            for (double f = 0.0; f < 4.0; f += 1.0 / 64) {
                const double exact = disk_adaptive(p, f * rho, rho);
                worst = std::max(worst, std::abs(bake::disk_integral(p, f * rho, rho) - exact) / exact);
            }
            const double area = kPi * rho * rho, exact = disk_adaptive(p, 4 * rho, rho);
            const double jump = bake::vertex_disk_term(p, 4 * rho, area) / exact - 1;
            std::printf("%-15s rho = %.2f: GL8 worst rel. error %.1e, far field at 4 rho %+.2f %%\n", name, rho, worst,
                        100 * jump);
            // The rule is accurate to 1e-3 for disks up to the profile's length (Burley: any).
            EXPECT_LT(worst, (p.kind == ProfileKind::Burley || rho <= 1.0) ? 1e-3 : 0.05) << name << " ρ = " << rho;
            EXPECT_LT(std::abs(jump), rho <= 0.25 ? 0.02 : 1.0) << name << " ρ = " << rho;
        }
    const auto p = ChannelProfile::burley(1.0);
    EXPECT_EQ(bake::disk_integral(p, 0.0, 0.7), dev::profile_cdf(p, 0.7));
    EXPECT_NEAR(bake::disk_integral(p, 1e-9, 0.7), dev::profile_cdf(p, 0.7), 1e-12);
    EXPECT_EQ(bake::vertex_disk_term(p, 0.0, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(bake::vertex_disk_term(p, 10.0, 1.0), dev::profile_value(p, 10.0));
}

// ---------------------------------------------------------------------------------------------
// reference_tm

TEST(ReferenceTm, FlatGridIsOneAndBeatsThePointSum)
{
    const double s = 1.0;  // spacing = d
    const PreparedMesh m = prepare_mesh(dev::procedural::grid(200, float(s)));
    const uint32_t centre = nearest_vertex(m, {0, 0, 0});
    const std::vector<float> ao(m.vertex_count(), 0.0f);
    const Material mat = burley_material(glm::dvec3(s), glm::vec3(0.8f));
    const auto t0 = std::chrono::steady_clock::now();
    const double tm = reference_tm(m, ao, mat, std::vector<uint32_t>{centre})[0].x;
    const double seconds = seconds_since(t0);
    // The point sum: self disk exact, every neighbour A_j·R(r).
    const ChannelProfile& p = mat.profile[0];
    double point = dev::profile_cdf(p, std::sqrt(m.areas[centre] / kPi));
    for (uint32_t j = 0; j < m.vertex_count(); ++j)
        if (j != centre)
            point += m.areas[j] *
                     dev::profile_value(p, glm::distance(glm::dvec3(m.positions[j]), glm::dvec3(m.positions[centre])));
    std::printf(
        "flat grid 201x201, spacing = d: vertex-disk t_m = %.6f (%.3f %%), point sum %.6f (%.3f %%), %.1f Mpairs/s\n",
        tm, 100 * (tm - 1), point, 100 * (point - 1), m.vertex_count() / seconds * 1e-6);
    EXPECT_NEAR(tm, 1.0, 0.01);
    EXPECT_LT(point, 0.985);
    EXPECT_GT(point, 0.96);
}

TEST(ReferenceTm, StiffAndSoftLimits)
{
    const PreparedMesh m = prepare_mesh(dev::procedural::grid(20, 0.05f));
    const std::vector<float> ao = ao_pattern(m.vertex_count());
    const double diag = m.diagonal;
    // d → 0: only the self disk counts, fully: t_m = 1 − A_o.
    const auto stiff = reference_tm(m, ao, burley_material(glm::dvec3(1e-6 * diag), glm::vec3(0.8f)));
    for (size_t i = 0; i < stiff.size(); ++i) ASSERT_NEAR(stiff[i].x, 1.0 - ao[i], 1e-9) << i;
    // d → ∞: R ≈ 1/(4πd r), so t_m ∝ 1/d.
    const auto a = reference_tm(m, ao, burley_material(glm::dvec3(1e6 * diag), glm::vec3(0.8f)));
    const auto b = reference_tm(m, ao, burley_material(glm::dvec3(1e7 * diag), glm::vec3(0.8f)));
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_GT(a[i].x, 0.0);
        ASSERT_NEAR(a[i].x, 10.0 * b[i].x, 1e-5 * a[i].x) << i;
    }
}

TEST(ReferenceTm, ScaleInvariantForEveryProfileKind)
{
    const TriangleMesh grid = dev::procedural::grid(16, 0.1f);
    const PreparedMesh m = prepare_mesh(grid);
    const std::vector<float> ao = ao_pattern(m.vertex_count());
    const double w[3] = {0.3, 0.5, 0.2}, v[3] = {0.001, 0.01, 0.05};
    Material mixed = burley_material(glm::dvec3(0.1, 0.2, 0.05), glm::vec3(0.8f));
    mixed.profile[1] = ChannelProfile::dipole(20.0, 1.0, 1.3);
    mixed.profile[2] = ChannelProfile::gaussians(w, v);
    const auto base = reference_tm(m, ao, mixed);
    // Powers of two scale the float mesh exactly: agreement to rounding. Decimal factors
    // also round the positions (≈ 6e-8 relative).
    for (const auto& [factor, tol] :
         {std::pair{0x1p-13f, 1e-9}, std::pair{0x1p13f, 1e-9}, std::pair{1e-4f, 2e-6}, std::pair{1e4f, 2e-6}}) {
        const double f = factor;  // the float factor exactly, for the mesh and the material
        const PreparedMesh ms = prepare_mesh(scaled(grid, factor));
        const auto t = reference_tm(ms, ao, mixed.scaled(f));
        for (size_t i = 0; i < t.size(); ++i)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(t[i][c], base[i][c], tol * base[i][c]) << "scale " << f << " vertex " << i;
    }
    // Subsets give the same values; the grey material is computed once and copied.
    const std::vector<uint32_t> subset = {3, 100, 3};
    const auto some = reference_tm(m, ao, mixed, subset);
    for (size_t k = 0; k < subset.size(); ++k) EXPECT_EQ(some[k], base[subset[k]]);
    const auto grey = reference_tm(m, ao, burley_material(glm::dvec3(0.1), glm::vec3(0.8f)), subset);
    EXPECT_EQ(grey[0].x, grey[0].z);
    EXPECT_EQ(grey[0].x, base[3].x);
}

TEST(ReferenceTm, ThinSlabIsMoreTranslucentThanThickBlock)
{
    const double d = 0.2, thickness = 0.2;  // Burley d equal to the slab thickness
    const Material mat = burley_material(glm::dvec3(d), glm::vec3(0.8f));
    auto top_centre_tm = [&](float bottom) {
        const PreparedMesh m = prepare_mesh(dev::procedural::box({-4, -4, bottom}, {4, 4, 0}, 40));
        const std::vector<float> ao = reference_ao(m, AoSettings{.rays = 64});
        return reference_tm(m, ao, mat, std::vector<uint32_t>{nearest_vertex(m, {0, 0, 0})})[0].x;
    };
    const double slab = top_centre_tm(-float(thickness)), block = top_centre_tm(-8.0f);
    // Half-space: 1. Slab: the bottom face adds about ∫ R over a parallel plane at distance h,
    // 1 − cdf(h) (the vertex-disk rule measures it with in-plane distances, so only roughly).
    const double bottom = 1.0 - dev::profile_cdf(mat.profile[0], thickness);
    std::printf("top-face centre: slab t_m = %.4f, block t_m = %.4f, 1 + (1 - cdf(h)) = %.4f\n", slab, block,
                1 + bottom);
    EXPECT_NEAR(block, 1.0, 0.02);
    EXPECT_GT(slab, block + 0.5 * bottom);
    EXPECT_LT(slab, block + 1.5 * bottom);
}

TEST(ReferenceTm, BunnySpeedAndErrors)
{
    const PreparedMesh m = prepare_mesh(load_mesh(test::asset("bunny00.off")));
    const std::vector<float> ao = reference_ao(m, AoSettings{.rays = 32}, {});
    const Material jade_mat = material_preset("jade", 100.0);  // the bunny is about 1 unit: 100 mm
    std::vector<uint32_t> subset;
    for (uint32_t i = 0; i < m.vertex_count(); i += 600) subset.push_back(i);
    const auto t0 = std::chrono::steady_clock::now();
    const auto tm = reference_tm(m, ao, jade_mat, subset);
    const double seconds = seconds_since(t0);
    const double pairs = double(subset.size()) * m.vertex_count();
    std::printf("reference_tm bunny (jade, RGB): %zu x %zu pairs in %.2f s = %.1f Mpairs/s (x3 channels)\n",
                subset.size(), m.vertex_count(), seconds, pairs / seconds * 1e-6);
    RecordProperty("mpairs_per_s", std::to_string(pairs / seconds * 1e-6));
    for (const auto& t : tm)
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(t[c]) && t[c] >= 0.0);
            EXPECT_LT(t[c], 3.0);
        }
    EXPECT_THROW(reference_tm(m, std::vector<float>(3, 0.0f), jade_mat), Error);
    EXPECT_THROW(reference_tm(m, ao, material_preset("opaque", 1.0), subset), Error);
    EXPECT_THROW(reference_tm(m, ao, jade_mat, std::vector<uint32_t>{uint32_t(m.vertex_count())}), Error);
    std::vector<float> bad = ao;
    bad[1] = std::nanf("");
    EXPECT_THROW(reference_tm(m, bad, jade_mat, subset), Error);
}
