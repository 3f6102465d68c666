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
// (load_scene, jade/io.hpp), and so is the on-disk bake cache (cached_bakes, jade/cache.hpp). Threading and lifetime as jade::Renderer: one thread, destroy
// before the Context. Errors: jade::Error naming the object and what is wrong.
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
/// baking its own (PassKind::SharedBake).
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
    bool deforming() const { return deformer.has_value(); }
};

struct Scene {
    std::string name;  ///< file name or "procedural"
    std::vector<SceneObject> objects;
};

/// What a pass does.
enum class PassKind : uint32_t {
    CacheRead = 0,    ///< static t_m read from the bake cache: no GPU work
    StaticBake = 1,   ///< AO + t_m once, before the first frame (Baker::bake); buffers freed after
    Deform = 2,       ///< per frame: MeshDeformer (positions, normals, areas on the GPU)
    DynamicBake = 3,  ///< per frame: DynamicBake (refit of both trees, AO, t_m)
    Draw = 4,         ///< per frame: Renderer (the object's shader variant)
    SharedBake =
        5,  ///< once: an earlier instance's static bake, its scattering normals turned (SceneObject::instance_of)
};
/// "cache read", "static bake", "deform", "dynamic bake", "draw", "shared bake".
std::string_view pass_kind_name(PassKind kind);

/// One GPU buffer a pass allocates; `bytes` is an estimate (see plan_scene).
struct BufferEstimate {
    std::string name;
    uint64_t bytes = 0;
    bool image = false;  ///< an image (the LUTs), not a buffer
};

struct PassPlan {
    PassKind kind = PassKind::Draw;
    bool per_frame = false;  ///< runs every frame (else once, in SceneRenderer's constructor)
    bool resident = false;   ///< its buffers stay allocated while the SceneRenderer lives
    std::vector<BufferEstimate> buffers;
    uint64_t bytes() const;         ///< Σ buffers and images
    uint64_t buffer_bytes() const;  ///< Σ buffers only (comparable with the device buffer bytes the Context allocated)
};

/// The variant of shaders/mesh.frag an object is drawn with (its specialisation constants).
struct ShaderVariant {
    ShadingMode mode = ShadingMode::Tm;
    uint32_t channels = 3;  ///< LUT fetches per light: 1 grey, 3 RGB (Lambert: 3, unused)
};

struct ObjectPlan {
    std::string name;
    size_t bake_vertices = 0, triangles = 0;  ///< after prepare_mesh
    bool opaque = false, deforming = false;
    uint32_t channels = 3;  ///< t_m channels baked: 1 grey, 3 RGB, 0 opaque
    ShaderVariant variant;
    uint64_t bake_key = 0;  ///< static translucent objects: the cache key (jade/cache.hpp)
    bool cached = false;    ///< the bake source already holds this bake (CacheRead)
    std::vector<PassPlan> passes;
    uint64_t resident_bytes() const;   ///< buffers held while drawing
    uint64_t transient_bytes() const;  ///< peak of the once-only passes, freed before drawing
    bool runs(PassKind kind) const;
};

struct ScenePlan {
    std::vector<ObjectPlan> objects;
    /// Held once for all objects while drawing: the translucency LUT (every Renderer of the
    /// scene shares it, jade/render.hpp).
    std::vector<BufferEstimate> shared;
    uint64_t shared_buffer_bytes() const;  ///< `shared` without the images
    uint64_t resident_bytes() const;
    /// The largest once-only pass: static bakes run one after the other, each freed at once.
    uint64_t transient_peak_bytes() const;
    /// Human-readable, as `jade plan` prints it.
    std::string describe() const;
};

/// Where a static bake came from (StaticBakeSource::bake, jade::io's bake_with_cache).
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

/// Where static bakes come from. Default (empty functions): never cached, baked each time.
/// jade::io's cached_bakes(cache) (jade/cache.hpp) reads and fills a BakeCache.
struct StaticBakeSource {
    struct Lookup {
        uint64_t key = 0;    ///< bake_key() of the bake
        bool holds = false;  ///< a valid entry is already there
    };
    /// Whether a bake of (mesh, material, settings) is already available (plan only).
    std::function<Lookup(const PreparedMesh&, const Material&, const BakeSettings&)> lookup;
    /// Produces it: from the cache, or bakes (and stores).
    std::function<CachedBake(Context&, const PreparedMesh&, const Material&, const BakeSettings&)> bake;
};

/// Every static translucent object drawn with t_m = 0, nothing baked or read: the same draws
/// as a baked scene (benchmarks compare against it; t_m = 0 shades exactly as Lambert).
StaticBakeSource never_baked();

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

/// What ran, for --verbose and tests.
struct PassRecord {
    std::string object;
    PassKind kind;
    double wall_ms = 0;
    std::string note;  ///< e.g. the cache's reason for a miss
};

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
    /// Every pass run so far, in order (once-only passes first).
    const std::vector<PassRecord>& passes_run() const;
    /// The t_m each object is drawn with (per bake vertex; empty for opaque objects). For a
    /// deforming object, the last frame's, read back from the GPU by this call (frames never
    /// read it back themselves).
    const std::vector<glm::vec3>& tm(size_t object) const;

    /// Runs the per-frame passes at time `t` (seconds), then draws every object into one image
    /// (one depth buffer; objects after the first are drawn over the others). `settings.mode`
    /// is ignored: each object uses its planned variant. Near and far planes fit the whole
    /// scene unless the camera gives them.
    RenderedImage render(double t, const Camera& camera, std::span<const Light> lights, const RenderSettings& settings);
    /// The scene's bounds (world space, rest pose).
    glm::vec3 bbox_min() const;
    glm::vec3 bbox_max() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace jade
