// jade/dev/clock.hpp - the wall clock Jade's timings use (BakeTimings::wall_ms, the passes'
// wall_ms, the CLI's benchmarks): a monotonic clock, milliseconds as double. Header-only.
#pragma once

#include <chrono>

namespace jade {

using Clock = std::chrono::steady_clock;

/// Wall-clock milliseconds from t0 to now.
inline double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace jade
