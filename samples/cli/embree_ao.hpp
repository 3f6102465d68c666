// embree_ao.hpp - the AO pass traced by Intel Embree 3 on the CPU, the yardstick of `jade bench
// bake` and `jade bench deform` (the speed target: the GPU pass within 2× of Embree's time at
// equal rays). Same rays as the GPU pass and reference_ao (jade::ao_ray_direction),
// same origin offset and max distance; single-precision occlusion queries (rtcOccluded1) on all
// hardware threads. Only the benchmarks link Embree (libembree-dev); a build without it says so.
#pragma once

#include <jade/bake.hpp>
#include <jade/mesh.hpp>
#include <jade/dev/reference.hpp>

namespace jade::cli {

/// Times dev::bake_ao (GPU timestamps) and Embree on the same rays alternately, `pairs`
/// times, and prints the medians, the median of the per-pair ratios GPU / Embree with its
/// quartiles, and how many vertices' AO agree exactly. Embree is timed on the queries alone
/// (its ray directions are made before the clock starts; the GPU pass's time includes making
/// its rays): the strictest yardstick. One line saying why when this build has no Embree.
/// Throws jade::Error when Embree reports an error.
void compare_ao_with_embree(Baker& baker, const PreparedMesh& mesh, const AoSettings& settings, unsigned pairs);

}  // namespace jade::cli
