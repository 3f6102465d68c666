// jade/bake.hpp - the precompute of the poster's equation (1), on the GPU (its float64 CPU
// reference, the same rays and discretisation: jade/dev/reference.hpp).
//
//   A_o(x)  ambient occlusion: the fraction of cosine-weighted hemisphere rays from x (offset
//           along the vertex normal by ε) that hit the mesh within max_distance. 0 = open.
//   t_m(x)  translucency magnitude: ∫_S R(|x − s|)(1 − A_o(s)) dS, per colour channel,
//           unitless (R is normalised to 1 over the plane, so t_m = 1 on an open plane).
//
// Discretisation (the "vertex-disk rule", shared by GPU and CPU): each bake vertex j stands
// for a flat disk of its area A_j (radius ρ_j = √(A_j/π)) centred on it, carrying 1 − A_o(j).
//   t_m(i) = (1 − A_o(i))·cdf(ρ_i)                              (self disk, exact)
//          + Σ_{j≠i} (1 − A_o(j))·D(r_ij, ρ_j)                  (neighbours)
//   D(r, ρ) = ∫ over the disk of radius ρ' = min(ρ, 0.6·r) at distance r of R
//             + (A_j − πρ'²)·R(r)                             when r < 4ρ_j (near field)
//           = A_j · R(r)                                         otherwise (point)
// (The cap ρ' keeps a large neighbour's disk from covering the target on irregular meshes,
// which for a stiff profile would count a second self term; the rest of its area stays a
// point. On regular meshes ρ ≈ 0.56·r and the cap does nothing.)
// D is integrated exactly in distance t from x: cdf(max(ρ−r,0)) + ∫_{|r−ρ|}^{r+ρ} R(t)·2t·α(t) dt
// with α(t) = acos((t² + r² − ρ²)/(2tr)) the half-angle of the arc of the circle of radius t
// inside the disk, by an 8-point Gauss–Legendre rule in φ where t = c − h·cos φ.
// Summing neighbours as points instead would be 2.6 % low on a flat grid of spacing d.
#pragma once

#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/noncopyable.hpp>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <span>
#include <vector>

namespace jade {

struct AoSettings {
    uint32_t rays = 64;             ///< rays per vertex (any count ≥ 1)
    bool low_discrepancy = true;    ///< Hammersley + per-vertex Cranley–Patterson rotation; false: i.i.d.
    uint32_t seed = 1;              ///< results are deterministic for a fixed seed
    float max_distance_rel = 0.1f;  ///< max hit distance, × the mesh diagonal
    float ray_offset_rel = 1e-4f;   ///< ε: ray origin offset along the normal, × the diagonal
};

/// The per-vertex thickness t̄(x): the mean distance, mesh units, from x (offset against the
/// normal by ε) to the nearest surface (either face) along `rays` rays inwards, uniform in solid
/// angle in the cone of half-angle `cone_degrees` about −n (the shape-diameter-function idea,
/// Shapira et al. 2008, without its outlier rejection: t̄ feeds e^{−σ_t t̄}, where a long ray
/// should count). A ray that meets nothing within max_distance counts as max_distance. Rays: the
/// AO pass's Hammersley set with a per-vertex rotation (seed), mapped to the cone. Distances are
/// measured from x itself (the offset's ε/cos θ is added back) and summed in fixed point
/// (2^-22 × max_distance), so the result is deterministic.
struct ThicknessSettings {
    uint32_t rays = 32;             ///< rays per vertex, 0..1023; 0: no thickness pass
    float cone_degrees = 60.0f;     ///< half-angle of the cone about −n, (0, 90]
    float max_distance_rel = 1.0f;  ///< cap on a ray's distance, × the mesh diagonal
    float ray_offset_rel = 1e-4f;   ///< ε: ray origin offset against the normal, × the diagonal
    uint32_t seed = 2;
    bool enabled() const { return rays > 0; }
};

class Context;

namespace dev {
struct BakeStudy;  // jade/dev/bake.hpp: variants of the passes, for measuring them
struct BakerAccess;
}  // namespace dev

/// How t_m's far field is summed.
enum class TmMethod {
    Auto,       ///< the fastest that meets the quality's bound (rule: docs/bake.md, "Choosing the far field")
    Exact,      ///< all pairs, O(n²): the GPU ground truth
    Clustered,  ///< error-controlled Barnes–Hut far field, O(n log n)
    Grid,       ///< the profile's smooth part on 3-D grids, the rest exact nearby: O(n + cells)
};

/// Quality presets: the AO ray count and the clustered far field's opening ratio θ
/// (BakeSettings::tm_opening_ratio, shaders/tm_cluster.comp).
///   Draft: 16 rays, θ = 1.6   Default: 64 rays, θ = 1.2   High: 256 rays, θ = 0.4
/// (θ's max relative t_m error on the bunny, Burley RGB with d at 1 %, 5 %, 20 % of the diagonal:
/// 1.6 → 8.4e-3, 1.2 → 2.5e-3, 0.8 → 8e-4; tests assert default ≤ 1 %, high ≤ 0.1 %.)
enum class Quality { Draft, Default, High };

struct BakeSettings {
    AoSettings ao;
    /// The thickness pass, run only for a material whose transmission is enabled (it is what
    /// the term reads). Quality presets: 16 / 32 / 64 rays.
    ThicknessSettings thickness;
    TmMethod method = TmMethod::Auto;
    /// The far field's accuracy knob θ, an opening ratio: a node of the cluster tree with radius
    /// s at distance r is summed as one monopole + quadrupole when s ≤ θ·min(r, ℓ), ℓ = R/|R'|
    /// the profile's decay length at r. The error is third order in θ; measured max relative
    /// error on the bunny and the dragon (d = 5 % of the diagonal): θ = 1: 1.6e-3, 0.7: 4.7e-4,
    /// 0.5: 1.6e-4, 0.3: 1.6e-5.
    float tm_opening_ratio = 1.2f;
    /// The grid far field's accuracy knob (TmMethod::Grid): grid cells per Gaussian σ, in
    /// [1.5, 4]. It also sets how far the exact near field reaches (2.5·resolution mean vertex
    /// spacings) and the finest Gaussian (that reach / resolution); memory grows as its cube.
    /// Measured max relative error: docs/bake.md.
    float tm_grid_resolution = 2.0f;
    static BakeSettings preset(Quality q);  ///< the Quality table above
    /// Set by the tools and tests only (jade/dev/bake.hpp); null: the defaults.
    std::shared_ptr<const dev::BakeStudy> study;
};

/// GPU time per stage (timestamp queries) and wall time, milliseconds. setup_ms: host time
/// building the BVH, cluster tree and near-field lists before the GPU passes.
struct BakeTimings {
    std::vector<std::pair<std::string, double>> gpu_stages;
    double gpu_total_ms = 0, wall_ms = 0, setup_ms = 0;
};

/// What a bake produced, one value per bake vertex of the PreparedMesh it was given.
struct BakeResult {
    std::vector<float> ao;         ///< per bake vertex, [0,1]
    std::vector<glm::vec3> tm;     ///< per bake vertex, linear RGB, unitless
    std::vector<float> thickness;  ///< per bake vertex, mesh units; empty without the pass
    /// Per bake vertex, unit length: the direction of Σ_c N_c, N_c = ∫ R_c(|x − s|)(1 − A_o(s))·n(s) dS,
    /// the mean normal of the surface the scattered light enters through, weighted as t_m is
    /// (the channels' profiles summed). The translucent diffuse term is lit along it
    /// (docs/shading.md): small bumps within the profile's reach smooth out, as light diffusing
    /// under the surface smooths them. The vertex normal where the sum vanishes (nothing lit
    /// within reach). Empty when t_m is not baked (bake_ao only, opaque materials).
    std::vector<glm::vec3> scattering_normal;
    /// Per bake vertex and channel, in [0, 1]: 1 − |N_c| / t_m,c, how much the normals within
    /// the channel's profile reach disagree (0 on a plane; ≈ ⟨θ²⟩/2 for a small angular spread
    /// θ about their mean; 1 when they cancel). A wide profile on a curved surface spreads its
    /// light over more directions: Material::spread_strength turns it into blur. Empty with
    /// scattering_normal.
    std::vector<glm::vec3> normal_spread;
    BakeTimings timings;
    TmMethod method_used = TmMethod::Exact;
    uint64_t tm_bytes = 0;  ///< device memory of the t_m passes: near lists, far field, sums
};

/// Runs the AO and t_m passes on the GPU. Keeps its compute pipelines between bakes; create
/// one per Context. Not thread-safe; use it from the Context's thread and destroy it before
/// the Context. Every bake records into Jade's own command buffers, submits them to the
/// Context's queue (the host's queue for an adopted Context) and blocks until they complete;
/// its GPU buffers are released when the call returns. Errors (jade::Error): an empty mesh,
/// `ao` of the wrong size, settings out of range, a failed Vulkan call.
class Baker : NonCopyable {
public:
    explicit Baker(Context& context);
    ~Baker();

    /// AO, the thickness (when settings.thickness.enabled()) then t_m (the material's profiles,
    /// per channel; one channel when grey()).
    BakeResult bake(const PreparedMesh& mesh, const Material& material, const BakeSettings& settings = {});

private:
    struct Impl;
    friend class DynamicBake;
    friend struct dev::BakerAccess;  // the partial bakes of jade/dev/bake.hpp (AO only, t_m from given AO)
    std::unique_ptr<Impl> impl_;
};

/// How much of the re-bake one DynamicBake::record() does (amortisation over frames).
///
/// AO (and the thickness rays, the same way): the rays of AoSettings are split into `ao_slices` interleaved slices (ray k belongs to
/// slice k mod ao_slices, so each slice is itself a stratified set); a record() re-traces one
/// slice, in turn, and keeps the other slices' hit counts from the frames that traced them.
/// t_m: the vertices, in the point tree's order (so each slice is a few compact patches of the
/// surface), are split into `tm_slices` ranges; a record() re-evaluates one range, the others
/// keep their value. Refits and the sources are updated every frame, with the AO they have. So
/// on a still mesh every frame equals the full re-bake; after the mesh stops moving, AO is exact
/// after ao_slices frames and t_m after ao_slices + tm_slices − 1; a moving mesh lags behind by
/// up to that many frames. The first record() after construction or set_amortisation does
/// everything. Meshes that TmMethod::Auto sums over all pairs (the small ones: docs/bake.md,
/// "Choosing the far field") always re-evaluate every vertex's t_m. `jade bench deform` measures the error
/// this adds against a from-scratch bake of each frame.
struct Amortisation {
    uint32_t ao_slices = 1;  ///< ≥ 1, divides AoSettings::rays and ThicknessSettings::rays; 1: every ray every frame
    uint32_t tm_slices = 1;  ///< ≥ 1; 1: every vertex's t_m every frame
    /// With ao_slices > 1: a vertex whose fresh AO slice hits a different number of times than
    /// the same rays did when that slice was last traced has moved against its surroundings, so
    /// its other AO slices are traced again in the same frame (the thickness rays keep one slice
    /// a frame). Where parts sweep past each other this removes much of the lag (docs/deform.md),
    /// at a cost that follows how much of the mesh moves that way; a still or rigidly moving
    /// mesh costs nothing extra. false: one slice a frame, always.
    bool retrace_changed = true;
};

/// The per-frame re-bake of a deforming mesh, all on the GPU (the poster's future work).
///
/// Built once from the rest pose: the triangle BVH's and the cluster tree's shapes, the
/// near-field candidate lists (with a margin: vertices may come up to 1.5× closer than at rest
/// before a disk pair is missed). Each frame, from the current positions, normals and areas
/// (same vertices and triangles), `record` refits both trees bottom-up and reruns AO and t_m;
/// no mesh data goes through the CPU. A refit keeps the tree's shape: for large deformations
/// build a new DynamicBake (a rebuild) now and then. AO distances stay fractions of the rest
/// pose's diagonal. Not thread-safe; uses the Baker's pipelines, so the Baker must outlive it.
class DynamicBake : NonCopyable {
public:
    DynamicBake(Baker& baker, const PreparedMesh& rest, const Material& material, const BakeSettings& settings = {});
    ~DynamicBake();

    /// The GPU buffers, one entry per bake vertex, tightly packed: positions and normals
    /// (float3, mesh units, unit normals), areas (float, units²) - written by a deformer (usage:
    /// storage, transfer destination) - and the results ao (float), t_m (float3) and thickness
    /// (float, mesh units; VK_NULL_HANDLE when BakeSettings::thickness is off), and the
    /// per-channel normal sums N_c (three float3 per vertex, channel-minor: what
    /// BakeResult::scattering_normal and normal_spread are made of; Renderer::record_vertex_update
    /// takes them as they are).
    struct Buffers {
        VkBuffer positions, normals, areas, ao, tm;
        uint32_t vertex_count;
        VkBuffer thickness = VK_NULL_HANDLE;
        VkBuffer scattering_normal = VK_NULL_HANDLE;
    };
    Buffers buffers() const;

    /// Records the re-bake into `cmd` (a compute-capable queue of the Baker's device). It begins
    /// with a barrier that makes earlier compute-shader and transfer writes to the inputs
    /// visible; when the command buffer has executed, ao and tm hold the results (written by
    /// compute shaders: make them visible to their next reader with a barrier).
    void record(VkCommandBuffer cmd);
    /// As record(cmd), taking the inputs from the caller's buffers of the same layout (e.g. a
    /// MeshDeformer's, jade/deform.hpp): they are copied in first, after a barrier for earlier
    /// compute-shader or transfer writes to them.
    void record(VkCommandBuffer cmd, VkBuffer positions, VkBuffer normals, VkBuffer areas);

    /// Convenience: uploads the inputs, records, submits, waits and reads back. Throws
    /// jade::Error on sizes that do not match the rest pose or non-finite input.
    BakeResult bake(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                    std::span<const float> areas);
    /// Convenience for inputs already on the GPU (e.g. a MeshDeformer's buffers, after its
    /// deform() returned): records record(cmd, positions, normals, areas) with GPU timestamps
    /// per stage, submits, waits, and reads ao and tm back when `read_back` (else they are empty).
    BakeResult bake(VkBuffer positions, VkBuffer normals, VkBuffer areas, bool read_back = true);

    /// Re-bakes a part of the work per record() (see Amortisation). Waits for the device to
    /// be idle when the AO slice count changes (the hit-count buffer is reallocated). Throws
    /// jade::Error naming the field when ao_slices does not divide the ray count or a count is 0.
    void set_amortisation(const Amortisation& amortisation);
    const Amortisation& amortisation() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace jade
