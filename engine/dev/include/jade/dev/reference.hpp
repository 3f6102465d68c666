// jade/dev/reference.hpp - float64 CPU references of the bake (jade/bake.hpp): the same rays and
// the same vertex-disk rule as the GPU passes, in double precision, for validating a bake and
// for tools. Slow (all vertex pairs for t_m); an embedder that only bakes does not need them.
// Declared for jade::dev, defined in jade::jade.
#pragma once

#include <jade/bake.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace jade {

/// float64 CPU reference of the thickness pass: the same rays, intersected in double precision
/// (nearest hit) over a BVH. `vertices` as in reference_ao.
std::vector<double> reference_thickness(const PreparedMesh& mesh, const ThicknessSettings& settings,
                                        std::span<const uint32_t> vertices = {});

/// float64 CPU reference of the AO pass: the same rays as the GPU pass, intersected in double
/// precision over a BVH, on all hardware threads. `vertices` limits it to a subset (empty = all);
/// the result then holds one value per listed vertex.
std::vector<float> reference_ao(const PreparedMesh& mesh, const AoSettings& settings,
                                std::span<const uint32_t> vertices = {});

/// float64 CPU reference of t_m: brute force over all vertex pairs with the vertex-disk rule,
/// on all hardware threads. `ao` has one value per bake vertex. `vertices` as in reference_ao.
std::vector<glm::dvec3> reference_tm(const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                                     std::span<const uint32_t> vertices = {});

/// float64 CPU reference of BakeResult::scattering_normal and normal_spread, over the same
/// pairs and rule as reference_tm; one value per listed vertex.
struct ReferenceScattering {
    std::vector<glm::dvec3> normal;  ///< unit; the vertex normal where the sum vanishes
    std::vector<glm::dvec3> spread;  ///< per channel, [0, 1]
};
ReferenceScattering reference_scattering(const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                                         std::span<const uint32_t> vertices = {});

/// The direction of ray k of vertex `vertex` (unit, world space, cosine-distributed about
/// `normal`): the ray set both the GPU pass and reference_ao use.
glm::vec3 ao_ray_direction(glm::vec3 normal, uint32_t vertex, uint32_t k, const AoSettings& settings);

}  // namespace jade
