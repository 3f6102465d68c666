// shading/curvature.cpp - per-vertex mean curvature for the curvature shading mode.
#include <jade/dev/renderer.hpp>
#include <jade/error.hpp>
#include <jade/render.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace jade {

std::vector<float> mean_curvature(const PreparedMesh& mesh, uint32_t smoothing)
{
    const size_t n = mesh.vertex_count(), tris = mesh.triangle_count();
    if (mesh.normals.size() != n || mesh.areas.size() != n)
        throw Error("mean_curvature: the mesh has " + std::to_string(n) + " vertices but " +
                    std::to_string(mesh.normals.size()) + " normals and " + std::to_string(mesh.areas.size()) +
                    " areas");
    // Σ_j (cot α_ij + cot β_ij)(x_j − x_i), triangle by triangle: the angle at each corner
    // weighs the opposite edge. Slivers have cotangents in the thousands that are rounding
    // noise, not geometry: clamp them (|cot| ≤ 100 is an angle of 0.57°).
    std::vector<glm::dvec3> laplacian(n, glm::dvec3(0.0));
    for (size_t t = 0; t < tris; ++t) {
        const uint32_t v[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
        const glm::dvec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        for (int k = 0; k < 3; ++k) {
            const int a = (k + 1) % 3, b = (k + 2) % 3;  // the edge opposite corner k
            const glm::dvec3 ea = p[a] - p[k], eb = p[b] - p[k];
            const double sin_area = glm::length(glm::cross(ea, eb));
            if (!(sin_area > 0.0)) continue;
            const double cot = std::clamp(glm::dot(ea, eb) / sin_area, -100.0, 100.0);
            laplacian[v[a]] += cot * (p[b] - p[a]);
            laplacian[v[b]] += cot * (p[a] - p[b]);
        }
    }
    // Δx = −2H n on a smooth surface; the discrete Δx_i = laplacian_i / (2 A_i).
    std::vector<double> h(n, 0.0);
    for (size_t i = 0; i < n; ++i)
        if (mesh.areas[i] > 0.0f)
            h[i] = -glm::dot(laplacian[i], glm::dvec3(mesh.normals[i])) / (4.0 * double(mesh.areas[i]));

    // Area-weighted average over each vertex's 1-ring (itself included), `smoothing` times.
    std::vector<double> sum(n), weight(n);
    for (uint32_t it = 0; it < smoothing; ++it) {
        for (size_t i = 0; i < n; ++i) sum[i] = h[i] * mesh.areas[i], weight[i] = mesh.areas[i];
        for (size_t t = 0; t < tris; ++t)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = mesh.indices[3 * t + k], b = mesh.indices[3 * t + (k + 1) % 3];
                // An interior edge is seen from both adjacent triangles, so neighbours weigh
                // twice their area and the vertex itself once: a gentle low-pass.
                sum[a] += h[b] * mesh.areas[b], weight[a] += mesh.areas[b];
                sum[b] += h[a] * mesh.areas[a], weight[b] += mesh.areas[a];
            }
        for (size_t i = 0; i < n; ++i) h[i] = weight[i] > 0.0 ? sum[i] / weight[i] : h[i];
    }
    return std::vector<float>(h.begin(), h.end());
}

}  // namespace jade
