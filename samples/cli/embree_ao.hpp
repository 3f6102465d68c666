// embree_ao.hpp - the AO pass traced by Intel Embree 3 on the CPU, for `jade bench bake` and
// `jade bench deform` to measure the GPU pass against (the issue's speed target is "within 2×
// of Embree's time at equal rays"). Same rays as the GPU pass and reference_ao
// (jade::ao_ray_direction), same origin offset and max distance; single-precision occlusion
// queries (rtcOccluded1) on all hardware threads. Only the bench links Embree (libembree-dev);
// a build without it reports that it has none.
#pragma once

#include <jade/bake.hpp>
#include <jade/mesh.hpp>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace jade::cli {

struct EmbreeAo {
    std::vector<float> ao;  ///< per bake vertex, as BakeResult::ao
    double build_ms = 0;    ///< scene (BVH) build, wall
    double trace_ms = 0;    ///< the occlusion queries, wall, best of the repetitions
    unsigned threads = 1;
    std::string version;
};

/// Traces mesh's AO rays `repeat` times with Embree and keeps the fastest; nullopt when this
/// build has no Embree. Throws jade::Error when Embree reports an error.
std::optional<EmbreeAo> embree_ao(const PreparedMesh& mesh, const AoSettings& settings, unsigned repeat = 3);

/// Prints one benchmark line: Embree's time for the same rays, Mrays/s, the GPU pass's time
/// (gpu_ao_ms, same rays) as a multiple of it, and, given the GPU's AO, how many vertices agree.
void print_embree_line(const PreparedMesh& mesh, const AoSettings& settings, double gpu_ao_ms,
                       std::span<const float> gpu_ao = {});

}  // namespace jade::cli
