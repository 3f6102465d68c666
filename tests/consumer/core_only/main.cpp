// Links the core library alone and calls into each part of it that needs no device: mesh
// preparation, materials (a preset and one made from a medium), a camera, lights, a scene plan.
#include "core_headers.hpp"  // every core header (CMakeLists.txt)

#include <cstdio>

int main()
{
    const jade::TriangleMesh mesh = jade::procedural::sphere(1.0f, 8, 12);
    const jade::PreparedMesh sphere = jade::prepare_mesh(mesh);
    const jade::Material material = jade::material_preset("jade", 100.0);
    jade::Medium medium;
    medium.sigma_s = glm::dvec3(2.0);
    medium.sigma_a = glm::dvec3(0.1);
    const jade::Material from_medium = jade::Material::from_medium(medium);
    const jade::Camera camera = jade::Camera::framing(sphere.bbox_min, sphere.bbox_max);
    const std::vector<jade::Light> lights = jade::default_lights(camera);
    const jade::ScenePlan plan =
        jade::plan_scene({"core", {{"sphere", mesh, material, std::nullopt}}}, jade::SceneSettings{});
    const jade::BakeSettings draft = jade::BakeSettings::preset(jade::Quality::Draft);
    std::printf(
        "core_consumer: %zu vertices, albedo %g, %zu lights, plan of %llu bytes while drawing, draft bake of %u "
        "AO rays\n",
        sphere.vertex_count(), double(from_medium.albedo.r), lights.size(), (unsigned long long)plan.resident_bytes(),
        draft.ao.rays);
    const bool ok = sphere.vertex_count() > 0 && from_medium.albedo.r > 0.0f && lights.size() == 2 &&
                    plan.resident_bytes() > 0 && plan.describe().find("object 0 'sphere'") == 0;
    return ok ? 0 : 1;
}
