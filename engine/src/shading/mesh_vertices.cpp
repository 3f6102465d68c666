// shading/mesh_vertices.cpp - the renderer's vertices from a prepared mesh and its bake, checked.
#include "shading/mesh_vertices.hpp"

#include <jade/error.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace jade::shading {

MeshVertices build_vertices(const PreparedMesh& mesh, std::span<const glm::vec3> tm, std::span<const float> thickness,
                            std::span<const glm::vec3> scattering_normal, std::span<const glm::vec3> normal_spread,
                            std::span<const float> curvature)
{
    const size_t n = mesh.vertex_count();
    if (!scattering_normal.empty() && scattering_normal.size() != n)
        throw Error("Renderer::set_mesh: " + std::to_string(scattering_normal.size()) + " scattering normals for " +
                    std::to_string(n) + " vertices");
    if (!normal_spread.empty() && normal_spread.size() != n)
        throw Error("Renderer::set_mesh: " + std::to_string(normal_spread.size()) + " normal spreads for " +
                    std::to_string(n) + " vertices");
    if (!tm.empty() && tm.size() != n)
        throw Error("Renderer::set_mesh: " + std::to_string(tm.size()) + " t_m values for " + std::to_string(n) +
                    " vertices");
    if (!thickness.empty() && thickness.size() != n)
        throw Error("Renderer::set_mesh: " + std::to_string(thickness.size()) + " thickness values for " +
                    std::to_string(n) + " vertices");
    MeshVertices out;
    out.vertices.resize(n);
    float tm_min = INFINITY, tm_max = 0.0f;
    glm::vec3 tm_min_channel(n == 0 || tm.empty() ? 0.0f : INFINITY);
    for (size_t i = 0; i < n; ++i) {
        glm::vec3 t = tm.empty() ? glm::vec3(0.0f) : tm[i];
        // Each component on its own: t.x + t.y + t.z overflows for values near FLT_MAX, which
        // are valid (the shader clamps strength · t_m to the LUT's range).
        if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) || t.x < 0 || t.y < 0 || t.z < 0)
            throw Error("Renderer::set_mesh: t_m of vertex " + std::to_string(i) + " is negative or not finite");
        const float th = thickness.empty() ? 0.0f : thickness[i];
        if (!(std::isfinite(th) && th >= 0.0f))
            throw Error("Renderer::set_mesh: thickness of vertex " + std::to_string(i) + " is negative or not finite");
        glm::vec3 s = scattering_normal.empty() ? mesh.normals[i] : scattering_normal[i];
        const float s_len = glm::length(s);
        if (!(std::isfinite(s_len) && s_len > 0.0f))
            throw Error("Renderer::set_mesh: scattering normal of vertex " + std::to_string(i) +
                        " is zero or not finite");
        const glm::vec3 spread = normal_spread.empty() ? glm::vec3(0.0f) : normal_spread[i];
        if (!(spread.x >= 0.0f && spread.x <= 1.0f && spread.y >= 0.0f && spread.y <= 1.0f && spread.z >= 0.0f &&
              spread.z <= 1.0f))
            throw Error("Renderer::set_mesh: normal spread of vertex " + std::to_string(i) + " is not in [0, 1]");
        out.vertices[i] = {mesh.positions[i], mesh.normals[i], t, curvature[i], th, s / s_len, spread};
        const float mean = t.x / 3.0f + t.y / 3.0f + t.z / 3.0f;
        tm_min = std::min(tm_min, mean);
        tm_min_channel = glm::min(tm_min_channel, t);
        tm_max = std::max(tm_max, mean);
    }
    out.tm_min_mean = tm_min, out.tm_max_mean = tm_max, out.tm_min = tm_min_channel;
    std::vector<float> edges;
    edges.reserve(mesh.indices.size());
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        for (size_t e = 0; e < 3; ++e)
            edges.push_back(
                glm::distance(mesh.positions[mesh.indices[i + e]], mesh.positions[mesh.indices[i + (e + 1) % 3]]));
    if (!edges.empty()) {
        std::nth_element(edges.begin(), edges.begin() + ptrdiff_t(edges.size() / 2), edges.end());
        out.median_edge = edges[edges.size() / 2];
    }
    return out;
}

}  // namespace jade::shading
