// The canary for the synchronization-validation job (tests/CMakeLists.txt, sync_validation_*):
// that job asserts that the bake and render tests produce no message with the layer's
// synchronization validation on, which proves nothing unless the layer, set up the way
// gpu::Context sets it up, does report a real hazard. Two transfer writes to one buffer with
// no barrier between them are a write-after-write hazard: reported with synchronization
// validation, not reported without it, not reported once a barrier orders them.
// (Uses the engine's internal GPU layer: the public API records no raw commands.)
#include "gpu/buffer.hpp"
#include "gpu/context.hpp"

#include <jade/context.hpp>

#include <gtest/gtest.h>

#include <string>
#include <string_view>

namespace {

struct Outcome {
    uint64_t messages = 0;
    std::string log;
};

/// Fills one buffer twice in one command buffer, with or without a barrier in between.
Outcome fill_twice(bool sync_validation, bool barrier)
{
    Outcome out;
    jade::ContextOptions o;
    o.validation = true;
    o.synchronization_validation = sync_validation;
    o.log = [&](std::string_view line) { out.log += std::string(line) + "\n"; };
    jade::Context ctx(o);
    auto& gpu = ctx.gpu();
    jade::gpu::Buffer buffer(gpu, 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "sync canary");
    gpu.submit_and_wait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 1u);
        if (barrier) {
            VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
            mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
            mb.srcAccessMask = mb.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.memoryBarrierCount = 1;
            dep.pMemoryBarriers = &mb;
            vkCmdPipelineBarrier2(cmd, &dep);
        }
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 2u);
    });
    out.messages = ctx.validation_messages();
    return out;
}

TEST(SyncValidation, ReportsAWriteAfterWriteHazard)
{
    const Outcome o = fill_twice(true, false);
    EXPECT_NE(o.log.find("jade: Vulkan synchronization validation on"), std::string::npos) << o.log;
    EXPECT_GE(o.messages, 1u) << o.log;
    EXPECT_NE(o.log.find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos) << o.log;
}

TEST(SyncValidation, IsQuietWithABarrierAndWithoutSyncValidation)
{
    const Outcome ordered = fill_twice(true, true);
    EXPECT_EQ(ordered.messages, 0u) << ordered.log;
    const Outcome plain = fill_twice(false, false);  // core validation does not see hazards
    EXPECT_EQ(plain.messages, 0u) << plain.log;
    EXPECT_EQ(plain.log.find("synchronization validation on"), std::string::npos) << plain.log;
}

}  // namespace
