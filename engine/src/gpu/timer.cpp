#include "gpu/timer.hpp"

#include "gpu/context.hpp"

namespace jade::gpu {

GpuTimer::GpuTimer(Context& ctx, uint32_t max_stages) : ctx_(&ctx), capacity_(max_stages + 1)
{
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    ci.queryCount = capacity_;
    VkQueryPool p;
    check(vkCreateQueryPool(ctx.device(), &ci, nullptr, &p), "vkCreateQueryPool");
    pool_ = OwnedQueryPool(ctx.device(), p);
}

void GpuTimer::begin(VkCommandBuffer cmd)
{
    names_.clear();
    vkCmdResetQueryPool(cmd, pool_, 0, capacity_);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 0);
}

void GpuTimer::mark(VkCommandBuffer cmd, std::string stage)
{
    if (names_.size() + 1 >= capacity_) throw Error("GpuTimer: more stages than reserved");
    names_.push_back(std::move(stage));
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(names_.size()));
}

std::vector<std::pair<std::string, double>> GpuTimer::stages() const
{
    std::vector<std::pair<std::string, double>> out;
    if (names_.empty()) return out;
    std::vector<uint64_t> ticks(names_.size() + 1);
    check(vkGetQueryPoolResults(ctx_->device(), pool_, 0, uint32_t(ticks.size()), ticks.size() * 8, ticks.data(), 8,
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    const double ms_per_tick = ctx_->limits().timestampPeriod * 1e-6;
    for (size_t i = 0; i < names_.size(); ++i)
        out.emplace_back(names_[i], double(ticks[i + 1] - ticks[i]) * ms_per_tick);
    return out;
}

double GpuTimer::total_ms() const
{
    double t = 0;
    for (auto& [n, ms] : stages()) t += ms;
    return t;
}

}  // namespace jade::gpu
