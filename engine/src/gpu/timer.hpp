// gpu/timer.hpp - GPU time per stage from timestamp queries.
#pragma once

#include "gpu/vk.hpp"

#include <string>
#include <utility>
#include <vector>

namespace jade::gpu {

class Context;

using OwnedQueryPool = Owned<VkQueryPool, vkDestroyQueryPool>;

/// Records a timestamp before and after named stages of one command buffer. After the
/// submission has finished, `stages()` gives each stage's GPU time in milliseconds.
class GpuTimer {
public:
    GpuTimer(Context& ctx, uint32_t max_stages = 32);
    void begin(VkCommandBuffer cmd);                             ///< resets the pool, writes the first timestamp
    void mark(VkCommandBuffer cmd, std::string stage);           ///< ends `stage` (it began at the last mark)
    std::vector<std::pair<std::string, double>> stages() const;  ///< ms per stage
    double total_ms() const;

private:
    Context* ctx_;
    uint32_t capacity_;
    std::vector<std::string> names_;
    OwnedQueryPool pool_;
};

}  // namespace jade::gpu
