#include "scene.hpp"

#include <jade/io.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace samples::viewer {

namespace {

double now_ms()
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

jade::TriangleMesh load(const std::string& arg)
{
    if (arg == "sphere") return jade::procedural::sphere(1.0f, 48, 96);
    if (arg.empty() || arg == "bunny") {
        const char* assets = std::getenv("JADE_ASSETS");
        return jade::load_mesh(std::filesystem::path(assets ? assets : "assets") / "bunny00.off");
    }
    return jade::load_mesh(arg);
}

}  // namespace

const std::vector<std::string>& deformation_names()
{
    // "none", then one label per jade::DeformerKind in the enum's order (index - 1 is the kind).
    static const std::vector<std::string> names = {"none", "bend", "twist", "squash", "wave"};
    return names;
}

Scene::Scene(const jade::AdoptedVulkan& host, const std::string& mesh_arg, const ViewState& initial)
    : context_(host), baker_(context_), renderer_(context_)
{
    const jade::TriangleMesh mesh = load(mesh_arg);
    mesh_name_ = mesh.name;
    rest_ = jade::prepare_mesh(mesh);
    if (!mesh.baked_tm.empty()) baked_file_ = mesh;
    // As `jade render`: the object is taken to be 100 mm across unless told otherwise.
    mm_per_unit_ = rest_.diagonal > 0 ? 100.0 / rest_.diagonal : 1.0;
    update(initial);
}

Scene::~Scene() = default;

void Scene::update(const ViewState& state)
{
    // Keep the last bake's stage times on frames that bake nothing.
    std::vector<std::pair<std::string, double>> previous = std::move(times_.stages);
    times_.stages.clear();
    const bool material_changed = state.material != baked_material_ || state.quality != baked_quality_;
    if (material_changed && baked_material_ >= 0) baked_file_.reset();  // the file's t_m is for its own material
    if (material_changed) {
        material_ = jade::material_preset(jade::material_preset_names().at(size_t(state.material)), mm_per_unit_);
        strength_ = -1.0f;  // set_material below
    }
    if (state.strength != strength_) {
        material_.strength = state.strength;
        renderer_.set_material(material_);
        strength_ = state.strength;
    }
    if (state.deformation == 0) {
        if (material_changed || baked_deformation_ != 0) bake_static(state);
        deformer_.reset();
        rebake_.reset();
    } else {
        if (material_changed || state.deformation != baked_deformation_) {
            // A new rest-pose re-bake (trees, near-field lists) for the material and quality.
            rebake_.reset();
            const double t0 = now_ms();
            if (!deformer_) deformer_ = std::make_unique<jade::MeshDeformer>(context_, rest_);
            deformer_params_ = jade::ProceduralDeformer::fit(jade::DeformerKind(state.deformation - 1), rest_, 1);
            if (!material_.opaque) {  // an opaque material has no t_m to re-bake
                rebake_ = std::make_unique<jade::DynamicBake>(baker_, rest_, material_,
                                                              jade::BakeSettings::preset(state.quality));
                renderer_.set_mesh(rest_);  // triangles and curvature; the vertices follow on the GPU
            }
            times_.stages.emplace_back("re-bake setup (CPU)", now_ms() - t0);
        }
        deform_and_rebake(state);
    }
    if (times_.stages.empty()) times_.stages = std::move(previous);
    baked_material_ = state.material;
    baked_quality_ = state.quality;
    baked_deformation_ = state.deformation;
}

void Scene::bake_static(const ViewState& state)
{
    if (baked_file_ && !material_.opaque) {
        const double t0 = now_ms();
        renderer_.set_mesh(*baked_file_, baked_file_->baked_tm, baked_file_->baked_thickness,
                           baked_file_->baked_scattering_normal, baked_file_->baked_normal_spread);
        times_.stages.emplace_back("t_m from the file: set_mesh (CPU)", now_ms() - t0);
        return;
    }
    std::vector<glm::vec3> tm, scattering_normal, normal_spread;
    std::vector<float> thickness;
    if (!material_.opaque) {
        const jade::BakeResult r = baker_.bake(rest_, material_, jade::BakeSettings::preset(state.quality));
        times_.bake_wall_ms = r.timings.wall_ms;
        for (const auto& [name, ms] : r.timings.gpu_stages) times_.stages.emplace_back("bake " + name, ms);
        tm = r.tm;
        thickness = r.thickness;
        scattering_normal = r.scattering_normal;
        normal_spread = r.normal_spread;
    }
    const double t0 = now_ms();
    renderer_.set_mesh(rest_, tm, thickness, scattering_normal, normal_spread);
    times_.stages.emplace_back("set_mesh (CPU)", now_ms() - t0);
}

void Scene::deform_and_rebake(const ViewState& state)
{
    const double t0 = now_ms();
    const jade::DeformTimings d = deformer_->deform(deformer_params_, state.time);
    times_.stages.emplace_back("deform", d.deform_ms);
    times_.stages.emplace_back("normals", d.normals_ms);
    if (rebake_) {
        // GPU-resident: the re-bake reads the deformer's buffers and the renderer's vertices are
        // updated from them and from the new t_m, with no read-back.
        const jade::MeshDeformer::Buffers d = deformer_->buffers();
        const jade::BakeResult r = rebake_->bake(d.positions, d.normals, d.areas, /*read_back=*/false);
        for (const auto& [name, ms] : r.timings.gpu_stages) times_.stages.emplace_back("re-bake " + name, ms);
        const double t1 = now_ms();
        renderer_.update_vertices(d.positions, d.normals, rebake_->buffers().tm, rebake_->buffers().thickness,
                                  rebake_->buffers().scattering_normal);
        times_.stages.emplace_back("vertex update (wall)", now_ms() - t1);
    } else {  // opaque: no t_m, the deformed mesh as host data
        const double t1 = now_ms();
        renderer_.set_mesh(jade::deformed_mesh(rest_, deformer_->read()));
        times_.stages.emplace_back("set_mesh (CPU)", now_ms() - t1);
    }
    times_.bake_wall_ms = now_ms() - t0;
}

jade::Camera Scene::camera(const ViewState& state, float aspect) const
{
    const float yaw = glm::radians(state.yaw), pitch = glm::radians(state.pitch);
    const glm::vec3 direction(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
    // The same framing as `jade render` (bounds seen from +z by default), then the zoom.
    jade::Camera c = jade::Camera::framing(rest_.bbox_min, rest_.bbox_max, aspect, direction);
    if (state.zoom != 1.0f) c.eye = c.target + (c.eye - c.target) * state.zoom;
    // Explicit planes around twice the rest pose's bounding sphere: a deformed mesh drawn from
    // GPU-updated vertices may leave the rest bounds the renderer would fit the planes to.
    const float radius = 0.5f * glm::length(rest_.bbox_max - rest_.bbox_min), distance = glm::length(c.eye - c.target);
    c.near_plane = std::max(distance - 2.0f * radius, 1e-3f * radius);
    c.far_plane = distance + 2.0f * radius;
    return c;
}

std::vector<jade::Light> Scene::lights(const ViewState& state, const jade::Camera& camera) const
{
    std::vector<jade::Light> lights =
        state.figure1_lights ? jade::figure1_lights(camera) : jade::default_lights(camera);
    if (state.light_yaw == 0.0f && state.light_pitch == 0.0f) return lights;
    // Rotate the rig about the camera's up (yaw) and right (pitch) axes.
    const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const glm::mat4 rotation = glm::rotate(glm::mat4(1.0f), glm::radians(state.light_pitch), right) *
                               glm::rotate(glm::mat4(1.0f), glm::radians(state.light_yaw), up);
    for (jade::Light& l : lights) {
        if (l.type == jade::Light::Type::Directional)
            l.vector = glm::vec3(rotation * glm::vec4(l.vector, 0.0f));
        else
            l.vector = camera.target + glm::vec3(rotation * glm::vec4(l.vector - camera.target, 0.0f));
    }
    return lights;
}

void Scene::record(VkCommandBuffer cmd, const jade::RenderTarget& target, const ViewState& state, uint32_t samples)
{
    jade::RenderSettings settings;
    settings.width = target.width;
    settings.height = target.height;
    settings.mode = state.mode;
    settings.samples = samples;
    const jade::Camera cam = camera(state, float(target.width) / float(target.height));
    const std::vector<jade::Light> l = lights(state, cam);
    renderer_.record(cmd, target, cam, l, settings);
}

}  // namespace samples::viewer
