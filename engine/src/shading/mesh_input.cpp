// shading/mesh_input.cpp - Renderer::set_mesh for a mesh as loaded: it is prepared (welded) and
// the baked values per render vertex (TriangleMesh::baked_tm, baked_thickness, ...) are averaged over
// the render vertices of each bake vertex.
#include <jade/error.hpp>
#include <jade/render.hpp>

#include <string>
#include <vector>

namespace jade {

namespace {

// Per render vertex to per bake vertex: render vertices welded into one bake vertex carry the
// same baked value up to rounding; their mean.
template <class T>
std::vector<T> average_per_bake_vertex(const TriangleMesh& mesh, const PreparedMesh& prepared,
                                       std::span<const T> values, const char* what)
{
    if (values.empty()) return {};
    if (values.size() != mesh.positions.size())
        throw Error("Renderer::set_mesh: " + mesh.name + ": " + std::to_string(values.size()) + " " + what +
                    " values for " + std::to_string(mesh.positions.size()) + " render vertices");
    std::vector<T> out(prepared.vertex_count(), T(0.0f));
    std::vector<uint32_t> count(prepared.vertex_count(), 0);
    for (size_t i = 0; i < prepared.render_to_bake.size(); ++i)
        if (uint32_t b = prepared.render_to_bake[i]; b != PreparedMesh::kUnused) out[b] += values[i], ++count[b];
    for (size_t b = 0; b < out.size(); ++b)
        if (count[b]) out[b] /= float(count[b]);
    return out;
}

}  // namespace

void Renderer::set_mesh(const TriangleMesh& mesh, std::span<const glm::vec3> tm_per_render_vertex,
                        std::span<const float> thickness_per_render_vertex,
                        std::span<const glm::vec3> scattering_normal_per_render_vertex,
                        std::span<const glm::vec3> normal_spread_per_render_vertex)
{
    PreparedMesh prepared = prepare_mesh(mesh);
    const auto tm = average_per_bake_vertex(mesh, prepared, tm_per_render_vertex, "t_m");
    const auto thickness = average_per_bake_vertex(mesh, prepared, thickness_per_render_vertex, "thickness");
    // Welded vertices share one bake vertex's normal, so the mean is that normal (set_mesh
    // renormalises it); a mean that cancels is refused there, naming the vertex.
    const auto scattering_normal =
        average_per_bake_vertex(mesh, prepared, scattering_normal_per_render_vertex, "scattering normal");
    const auto normal_spread =
        average_per_bake_vertex(mesh, prepared, normal_spread_per_render_vertex, "normal spread");
    set_mesh(prepared, tm, thickness, scattering_normal, normal_spread);
}

}  // namespace jade
