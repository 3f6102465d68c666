// embree_ao.hpp - the AO pass traced by Intel Embree 3 on the CPU, the yardstick of `jade bench
// bake` and `jade bench deform` (the issue's speed target: the GPU pass "within 2× of Embree's
// time at equal rays"). Same rays as the GPU pass and reference_ao (jade::ao_ray_direction),
// same origin offset and max distance; single-precision occlusion queries (rtcOccluded1) on all
// hardware threads. Only the benchmarks link Embree (libembree-dev); a build without it says so.
#pragma once

#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/mesh.hpp>

#include <memory>
#include <string>
#include <vector>

namespace jade::cli {

/// A mesh's triangles in an Embree scene (high-quality build), ready to trace AO rays.
class EmbreeAo {
public:
    /// nullptr when this build has no Embree. Throws jade::Error when Embree reports an error.
    static std::unique_ptr<EmbreeAo> create(const PreparedMesh& mesh);
    virtual ~EmbreeAo() = default;

    /// Traces every vertex's rays; returns A_o per bake vertex, as Baker::bake_ao. The ray
    /// directions are made before the clock starts, so `trace_ms` (wall) times the queries alone,
    /// the strictest yardstick (the GPU pass's time includes making its rays).
    virtual std::vector<float> trace(const AoSettings& settings, double& trace_ms) = 0;

    double build_ms = 0;  ///< the scene (BVH) build, wall
    unsigned threads = 1;
    std::string version;
};

/// Times Baker::bake_ao (GPU timestamps) and Embree on the same rays alternately, `pairs`
/// times, and prints the medians, the median of the per-pair ratios GPU / Embree with its
/// quartiles, and how many vertices' AO agree exactly. One line saying why when there is no Embree.
void compare_ao_with_embree(Baker& baker, const PreparedMesh& mesh, const AoSettings& settings, unsigned pairs);

}  // namespace jade::cli
