// jade/dev/bake.hpp - variants of the bake's passes for measuring them (`jade report`, tests),
// not for production: BakeSettings::study holds them. Declared for jade::dev, defined in jade::jade.
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

}  // namespace jade::dev
