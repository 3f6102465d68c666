// shading/mesh_vertices.hpp - the renderer's vertex buffer contents (Renderer::set_mesh), built
// and checked on the host. Private to the engine.
#pragma once

#include "shading/mesh_pipeline.hpp"

#include <jade/mesh.hpp>

#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace jade::shading {

struct MeshVertices {
    std::vector<Vertex> vertices;
    float tm_min_mean = 0, tm_max_mean = 0;  // of the channels' mean t_m: the false-colour range
    glm::vec3 tm_min{0.0f};                  // per channel: the smallest t the evaluation must handle
    float median_edge = 0;                   // of the triangles' edges, mesh units (LightPathSampling::Auto)
};

/// One Vertex per bake vertex: t_m (empty: 0), thickness (empty: 0), scattering normal (empty: the
/// vertex normal; normalised) and normal spread (empty: 0). Throws jade::Error naming the vertex
/// for a size mismatch, a negative or non-finite t_m or thickness, a zero or non-finite scattering
/// normal, or a spread outside [0, 1].
MeshVertices build_vertices(const PreparedMesh& mesh, std::span<const glm::vec3> tm, std::span<const float> thickness,
                            std::span<const glm::vec3> scattering_normal, std::span<const glm::vec3> normal_spread,
                            std::span<const float> curvature);

}  // namespace jade::shading
