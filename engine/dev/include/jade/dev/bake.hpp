// jade/dev/bake.hpp - variants of the bake's passes for measuring them (`jade report`, tests),
// not for production: BakeSettings::study holds them; and the bake's passes one at a time (AO
// alone, t_m from given AO) for the benchmarks and tests. Declared for jade::dev, defined in
// jade::jade.
#pragma once

#include <jade/bake.hpp>

namespace jade::dev {

struct BakeStudy {
    /// All-pairs method only (TmMethod::Exact, or Auto on small meshes): accumulate the far
    /// field in float64 instead of compensated float32 sums (pair values stay float32). Needs
    /// DeviceInfo::float64 (jade::Error otherwise); for measuring what float32 sums cost in
    /// accuracy, slower on every device. Part of the bake cache's key.
    bool tm_float64_sums = false;
};
/// settings.study, or the defaults when it is null.
const BakeStudy& study_of(const BakeSettings& settings);
/// Sets settings.study to a copy of `study`.
void set_study(BakeSettings& settings, const BakeStudy& study);

/// Baker::bake's AO pass alone: one value in [0, 1] per bake vertex; `timings` (optional)
/// receives GPU/wall times. Submits and waits, as Baker::bake.
std::vector<float> bake_ao(Baker& baker, const PreparedMesh& mesh, const AoSettings& settings,
                           BakeTimings* timings = nullptr);
/// Baker::bake's t_m passes alone, from given AO (one value per bake vertex; jade::Error
/// otherwise); the result's `ao` is that AO.
BakeResult bake_tm(Baker& baker, const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                   const BakeSettings& settings = {});

}  // namespace jade::dev
