// samples/viewer - the Jade side of the viewer: an adopted jade::Context, the mesh, its bake,
// the deformation and the Renderer, driven by ViewState (what the panel edits).
//
// Static mesh: one jade::Baker::bake per change of material or quality. Deforming mesh: every
// frame jade::MeshDeformer::deform (GPU deform + normals + areas), then jade::DynamicBake (GPU
// refit of both trees, AO, t_m) and Renderer::set_mesh with the deformed vertices. The
// deformed vertices and t_m come back to the host once per frame because jade::Renderer takes
// its mesh from host memory (there is no public way to draw from a DynamicBake's buffers).
#pragma once

#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/deform.hpp>
#include <jade/render.hpp>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace samples::viewer {

/// Everything the panel (or the command line) sets. Angles in degrees.
struct ViewState {
    float yaw = 0.0f, pitch = 0.0f;              ///< orbit: the eye's direction from the target (0, 0: +z)
    float zoom = 1.0f;                           ///< eye distance / the framing distance
    float light_yaw = 0.0f, light_pitch = 0.0f;  ///< rotates the light rig about the camera's up and right axes
    bool figure1_lights = false;                 ///< jade::figure1_lights (back light) instead of jade::default_lights
    int material = 0;                            ///< index into jade::material_preset_names()
    float strength = 1.0f;                       ///< Material::strength (rad² per unit t_m)
    jade::ShadingMode mode = jade::ShadingMode::Tm;
    jade::Quality quality = jade::Quality::Default;
    int deformation = 0;  ///< 0: none, else 1 + jade::DeformerKind
    bool animate = true;  ///< advance the deformation's time with the wall clock
    double time = 0.0;    ///< deformation time, seconds
};

/// "none", "bend", "twist", "squash", "wave" (index = ViewState::deformation).
const std::vector<std::string>& deformation_names();

/// Named CPU (wall) and GPU times of the last update, milliseconds.
struct StageTimes {
    std::vector<std::pair<std::string, double>> stages;
    double bake_wall_ms = 0;  ///< the last static bake or per-frame re-bake, host time
};

class Scene {
public:
    /// mesh_arg: a mesh file, "bunny" (assets/bunny00.off or JADE_ASSETS) or "sphere".
    Scene(const jade::AdoptedVulkan& host, const std::string& mesh_arg, const ViewState& initial);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    /// Applies the state: re-bakes when the material or quality changed, rebuilds the deformer
    /// when the deformation changed, deforms and re-bakes when deforming. Waits for the GPU.
    void update(const ViewState& state);
    /// Records Jade's draw of the current mesh (Renderer::record).
    void record(VkCommandBuffer cmd, const jade::RenderTarget& target, const ViewState& state, uint32_t samples);

    jade::Camera camera(const ViewState& state, float aspect) const;
    std::vector<jade::Light> lights(const ViewState& state, const jade::Camera& camera) const;
    const StageTimes& times() const { return times_; }
    size_t vertex_count() const { return rest_.vertex_count(); }
    const std::string& mesh_name() const { return mesh_name_; }

private:
    jade::Context context_;
    jade::Baker baker_;
    jade::Renderer renderer_;
    std::string mesh_name_;
    jade::PreparedMesh rest_;
    /// A file written by `jade bake`: its t_m is drawn until the material or quality changes.
    std::optional<jade::TriangleMesh> baked_file_;
    jade::Material material_;
    double mm_per_unit_ = 1.0;
    std::unique_ptr<jade::MeshDeformer> deformer_;
    std::unique_ptr<jade::DynamicBake> rebake_;
    jade::ProceduralDeformer deformer_params_;
    StageTimes times_;
    // What the current bake and deformer were made for.
    int baked_material_ = -1, baked_deformation_ = -1;
    jade::Quality baked_quality_ = jade::Quality::Default;
    float strength_ = -1.0f;

    void bake_static(const ViewState& state);
    void deform_and_rebake(const ViewState& state);
};

}  // namespace samples::viewer
