// jade/scene.hpp - a scene that pays only for what it uses.
//
// A Scene is a list of objects (mesh, material, static or deforming). plan_scene() analyses it
// once into a ScenePlan: per object the passes it needs, the shader variant it is drawn with and
// the GPU buffers each pass allocates. SceneRenderer then runs exactly the planned passes:
//   opaque material      no bake at all; drawn with the Lambert variant (ShadingMode::Lambert)
//   static, translucent  one bake (AO + t_m) or a cache read; the bake's buffers (BVH, cluster
//                        tree, near lists, ...) are freed before the first frame; per frame
//                        only the draw runs
//   deforming            per frame: GPU deform (MeshDeformer), GPU re-bake (DynamicBake), draw
//   grey profiles        one channel baked and one LUT fetch when drawn (the CHANNELS = 1
//                        specialisation of shaders/mesh.frag); three otherwise
// Objects are in world space, in mesh units (a glTF scene: metres).
//
// All of this header is in the core library jade::jade. Reading a scene file is jade::io's
// (load_scene, jade/io.hpp). Where static bakes come from is the caller's (StaticBakeSource; the
// CLI's on-disk cache is jade/dev/cache.hpp). Threading and lifetime as jade::Renderer: one
// thread, destroy before the Context. Errors: jade::Error naming the object and what is wrong.
#pragma once

#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/deform.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/noncopyable.hpp>
#include <jade/render.hpp>

#include <glm/mat3x3.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace jade {

/// One object of a scene: a mesh in world space with one material.
/// This object is a rigid copy of an earlier one of the scene: the same vertices, in the same
/// order, at rotation · p + translation (rotation orthogonal, proper), with the same material.
/// A static bake is invariant under such a motion but for the scattering normal, which turns
/// with it, so the copy takes the earlier object's prepared mesh, moved, and its bake instead of
/// baking its own (the plan's shared bake).
struct InstanceOf {
    uint32_t object = 0;          ///< index of the earlier object in Scene::objects
    glm::mat3 rotation{1.0f};     ///< that object's world directions to this one's
    glm::vec3 translation{0.0f};  ///< mesh units
};

struct SceneObject {
    std::string name;   ///< for messages, plans and --verbose
    TriangleMesh mesh;  ///< world space, mesh units
    Material material;
    std::optional<ProceduralDeformer> deformer;  ///< set: the mesh deforms (per-frame passes)
    /// Set by load_scene for the second and later instances of a glTF primitive whose nodes move
    /// it rigidly (no scale) and keep its material; clear it to bake each instance on its own.
    std::optional<InstanceOf> instance_of;
};

struct Scene {
    std::string name;  ///< file name or "procedural"
    std::vector<SceneObject> objects;
};

namespace dev {
struct ScenePlanDetails;  // jade/dev/scene.hpp: per object, its passes, shader variant and buffers
struct SceneRendererAccess;
}  // namespace dev

/// What plan_scene found: the GPU memory the scene will take (estimates, see plan_scene) and
/// the plan in words.
struct ScenePlan {
    /// Held while drawing: every object's buffers and the translucency LUT that every Renderer of
    /// the scene shares (jade/render.hpp).
    uint64_t resident_bytes() const;
    /// The largest once-only pass: static bakes run one after the other, each freed at once.
    uint64_t transient_peak_bytes() const;
    /// Human-readable, as `jade plan` prints it: per object its passes and their buffers.
    std::string describe() const;
    /// Set by plan_scene; read by the tools and tests only (jade/dev/scene.hpp).
    std::shared_ptr<const dev::ScenePlanDetails> details;
};

/// Where a static bake came from (StaticBakeSource::bake).
enum class BakeSource {
    Opaque,  ///< the material is opaque: nothing baked, `result` empty (Lambert needs no t_m)
    Cache,   ///< read from a cache: no GPU work, no bake pipelines or buffers
    Baked,   ///< baked on the GPU (a Baker made for the call), and stored when there is a cache
};

struct CachedBake {
    BakeResult result;
    BakeSource source = BakeSource::Baked;
    std::string note;  ///< why the cache was not used ("missing", "checksum mismatch", ...)
};

/// Where static bakes come from: a host's own store of bakes, or the default (empty functions):
/// never cached, baked each time.
struct StaticBakeSource {
    struct Lookup {
        uint64_t key = 0;    ///< the store's key of the bake (0: none), for describe()
        bool holds = false;  ///< a valid entry is already there
    };
    /// Whether a bake of (mesh, material, settings) is already available (plan only).
    std::function<Lookup(const PreparedMesh&, const Material&, const BakeSettings&)> lookup;
    /// Produces it: from the cache, or bakes (and stores).
    std::function<CachedBake(Context&, const PreparedMesh&, const Material&, const BakeSettings&)> bake;
};

struct SceneSettings {
    BakeSettings bake = BakeSettings::preset(Quality::Default);
    /// Shading of translucent objects: Tm (the default) or TmFalseColor; opaque objects are
    /// always Lambert. Curvature is not a scene mode.
    ShadingMode mode = ShadingMode::Tm;
    RendererOptions renderer;  ///< as the SceneRenderer builds its Renderers (the LUT size is counted in the plan)
};

/// Analyses the scene (CPU only: prepares every mesh). Memory is estimated from the vertex and
/// triangle counts with the byte sizes of the structures engine/src/bake and engine/src/shading
/// upload (documented in bake/buffer_estimate.cpp); tests compare it with what the Context allocated.
/// Throws jade::Error naming the object for an empty or invalid mesh, or a Curvature mode.
ScenePlan plan_scene(const Scene& scene, const SceneSettings& settings, const StaticBakeSource& source = {});

/// Runs a plan: the once-only passes in the constructor, the per-frame passes and the draws in
/// render(). Keeps, per object, only a Renderer (mesh vertices with t_m, LUT) and, when the
/// object deforms, its MeshDeformer and DynamicBake. The Baker of static bakes is made for the
/// constructor and destroyed at its end.
class SceneRenderer : NonCopyable {
public:
    SceneRenderer(Context& context, const Scene& scene, const SceneSettings& settings,
                  const StaticBakeSource& source = {});
    ~SceneRenderer();

    const ScenePlan& plan() const;

    /// Runs the per-frame passes at time `t` (seconds), then draws every object into one image
    /// (one depth buffer; objects after the first are drawn over the others). `settings.mode`
    /// is ignored: each object uses its planned variant. Near and far planes fit the whole
    /// scene unless the camera gives them.
    RenderedImage render(double t, const Camera& camera, std::span<const Light> lights, const RenderSettings& settings);
    /// The scene's bounds (world space, rest pose).
    glm::vec3 bbox_min() const;
    glm::vec3 bbox_max() const;

private:
    friend struct dev::SceneRendererAccess;  // what ran and the t_m drawn (jade/dev/scene.hpp)
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace jade
