// jade/dev/scene.hpp - the details of a scene plan (per object the passes it needs, the shader
// variant it is drawn with and the GPU buffers each pass allocates) and what a SceneRenderer ran,
// for `jade plan`, `jade scene --verbose`, the benchmarks and tests. A host needs only ScenePlan's
// totals and describe() (jade/scene.hpp). Declared for jade::dev, defined in jade::jade.
#pragma once

#include <jade/scene.hpp>

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace jade::dev {

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
    uint64_t bake_key = 0;  ///< static translucent objects: the key the bake source gave (StaticBakeSource::Lookup)
    bool cached = false;    ///< the bake source already holds this bake (CacheRead)
    std::vector<PassPlan> passes;
    uint64_t resident_bytes() const;   ///< buffers held while drawing
    uint64_t transient_bytes() const;  ///< peak of the once-only passes, freed before drawing
    bool runs(PassKind kind) const;
};

/// What ScenePlan::details holds.
struct ScenePlanDetails {
    std::vector<ObjectPlan> objects;
    /// Held once for all objects while drawing: the translucency LUT (every Renderer of the
    /// scene shares it, jade/render.hpp).
    std::vector<BufferEstimate> shared;
    uint64_t shared_buffer_bytes() const;  ///< `shared` without the images
};
/// *plan.details, or no objects for a plan that plan_scene did not make.
const ScenePlanDetails& plan_details(const ScenePlan& plan);

/// Every static translucent object drawn with t_m = 0, nothing baked or read: the same draws
/// as a baked scene (benchmarks compare against it; t_m = 0 shades exactly as Lambert).
StaticBakeSource never_baked();

/// One pass a SceneRenderer ran.
struct PassRecord {
    std::string object;
    PassKind kind;
    double wall_ms = 0;
    std::string note;  ///< e.g. the cache's reason for a miss
};
/// Every pass run so far, in order (once-only passes first).
const std::vector<PassRecord>& passes_run(const SceneRenderer& renderer);
/// The t_m object `object` is drawn with (per bake vertex; empty for opaque objects). For a
/// deforming object, the last frame's, read back from the GPU by this call (frames never read
/// it back themselves).
const std::vector<glm::vec3>& object_tm(const SceneRenderer& renderer, size_t object);

}  // namespace jade::dev
