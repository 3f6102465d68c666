// Links the core library alone and calls into each part of it that needs no device: mesh
// preparation, materials, the LUT and bake references, curvature, a scene plan, text overlays.
#include "core_headers.hpp"  // every core header (CMakeLists.txt)

#include <cstdio>

int main()
{
    const jade::TriangleMesh mesh = jade::procedural::sphere(1.0f, 8, 12);
    const jade::PreparedMesh sphere = jade::prepare_mesh(mesh);
    // f(θ, 0) is Lambert: max(cos θ, 0) at 60 degrees.
    const double f = jade::lut_reference(0.5, 0.0);
    const jade::Material material = jade::material_preset("jade", 100.0);
    jade::AoSettings ao;
    ao.rays = 8;
    const std::vector<float> occlusion = jade::reference_ao(sphere, ao);
    const std::vector<float> curvature = jade::mean_curvature(sphere);
    const jade::ScenePlan plan =
        jade::plan_scene({"core", {{"sphere", mesh, material, std::nullopt}}}, jade::SceneSettings{});
    jade::RenderedImage image;
    image.width = image.height = 16;
    image.rgba.assign(16 * 16 * 4, 0.0f);
    jade::draw_text(image, 1, 1, "ok", glm::vec3(1.0f));
    std::printf(
        "core_consumer: %zu vertices, f(60 deg, 0) = %g, %zu AO values, %zu curvatures, plan of %zu objects, %s\n",
        sphere.vertex_count(), f, occlusion.size(), curvature.size(), plan.objects.size(),
        jade::quality_name(jade::parse_quality("draft")));
    const bool ok = sphere.vertex_count() > 0 && f > 0.0 && occlusion.size() == sphere.vertex_count() &&
                    curvature.size() == sphere.vertex_count() && plan.objects.size() == 1 && plan.resident_bytes() > 0;
    return ok ? 0 : 1;
}
