// shading/transmission_table.cpp - see transmission_table.hpp.
#include "shading/transmission_table.hpp"

#include "gpu/context.hpp"

#include "jade_shaders.hpp"
#include "shading_interface.h"  // struct TablePush, shared with transmission_table.comp

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace jade::shading {
namespace {

// TablePush: shading_interface.h, shared with transmission_table.comp.

constexpr uint32_t kMaxTexels = 1u << 16;

}  // namespace

TransmissionTable::TransmissionTable(gpu::Context& ctx) : ctx_(ctx)
{
    buffer_ = gpu::Buffer::from(ctx, std::vector<glm::uvec4>(4, glm::uvec4(0)),
                                VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                "transmission table");
    view_ = gpu::TexelView(ctx, buffer_, VK_FORMAT_R32G32B32A32_UINT, 16, "transmission table");
}

TransmissionTable::Layout TransmissionTable::table_layout(const Transmission& tr)
{
    // The range: until every exponential with a non-zero rate is below e^{−14} (8e-7); the
    // spacing: a step of 0.03 / (fastest rate), so that linear interpolation errs by at most
    // 0.03²/8 ≈ 1e-4 of the weights (docs/shading.md). Rates are capped as the shader caps them.
    double slowest = INFINITY, fastest = 0.0;
    for (int c = 0; c < 3; ++c)
        if (tr.sigma_t[c] > 0.0f)
            slowest = std::min(slowest, double(std::min(tr.sigma_t[c], 3e38f))),
            fastest = std::max(fastest, double(std::min(tr.sigma_t[c], 3e38f)));
    if (!std::isfinite(slowest)) slowest = fastest = 1.0;  // no decay at all: A is constant
    const double range = 14.0 / slowest;
    const uint32_t count = uint32_t(std::clamp(std::ceil(range * fastest / 0.03) + 1.0, 2.0, double(kMaxTexels)));
    return {count, range / double(count - 1)};
}

uint64_t TransmissionTable::bytes(const Transmission& tr)
{
    return tr.enabled() ? uint64_t(table_layout(tr).count) * 16 : 64;
}

void TransmissionTable::update(const Transmission& tr)
{
    if (held_ && held_->sigma_t == tr.sigma_t && held_->weight == tr.weight) return;
    const Layout layout = table_layout(tr);
    const uint32_t count = layout.count;
    const double step = layout.step;
    if (buffer_.size() < VkDeviceSize(count) * 16) {
        if (buffer_) ctx_.release_after_gpu(std::move(view_), std::move(buffer_));  // recorded draws may read it
        buffer_ = gpu::Buffer(ctx_, VkDeviceSize(count) * 16,
                              VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              "transmission table");
        view_ = gpu::TexelView(ctx_, buffer_, VK_FORMAT_R32G32B32A32_UINT, 16, "transmission table");
    }
    if (!kernel_)
        kernel_.emplace(ctx_, gpu::KernelDesc{"transmission_table",
                                              shaders::transmission_table_comp(),
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                              sizeof(TablePush),
                                              64,
                                              {}});
    const TablePush push{glm::vec4(glm::min(tr.sigma_t, glm::vec3(3e38f)), tr.weight), float(step), count};
    ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
        // After the reads of draws submitted earlier (the table is rewritten in place).
        gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE);
        kernel_->dispatch(cmd, count, push, {buffer_});
        // For every later draw on the queue.
        gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
    });
    map_ = glm::vec4(float(1.0 / step), float(count - 1), float(count - 2), 0.0f);
    held_ = tr;
}

}  // namespace jade::shading
