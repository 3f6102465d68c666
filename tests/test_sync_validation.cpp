// The canary for the synchronization-validation job (tests/CMakeLists.txt, sync_validation_*):
// that job asserts that the bake and render tests produce no message with the layer's
// synchronization validation on, which proves nothing unless the layer, set up the way
// gpu::Context sets it up, does report a real hazard. Two transfer writes to one buffer with
// no barrier between them are a write-after-write hazard: reported with synchronization
// validation, not reported without it, not reported once a barrier orders them. Also: nothing
// is reported at shutdown (no Vulkan object outlives its owner).
// (Uses the engine's internal GPU layer: the public API records no raw commands.)
#include "gpu/buffer.hpp"
#include "gpu/context.hpp"

#include <jade/dev/context.hpp>
#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/render.hpp>
#include <jade/dev/mesh.hpp>

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
    auto& gpu = gpu_of(ctx);
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
    out.messages = jade::dev::validation_messages(ctx);
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

TEST(SyncValidation, ShutdownLeavesNoVulkanObjectBehind)
{
    // Every Vulkan object is destroyed at shutdown. The layer reports a child still
    // alive at vkDestroyDevice / vkDestroyInstance (object tracker) through the log, which
    // outlives the context: a bake and renders in every mode, then everything destroyed, must
    // leave the log without a single validation line (synchronization validation on as well).
    std::string log;
    {
        jade::ContextOptions o;
        o.validation = true;
        o.synchronization_validation = true;
        o.log = [&](std::string_view line) { log += std::string(line) + "\n"; };
        jade::Context ctx(o);
        const jade::PreparedMesh box = jade::prepare_mesh(jade::dev::procedural::box({-1, -1, -1}, {1, 1, 1}, 3));
        const jade::Material m = jade::burley_material(glm::dvec3(0.3), glm::vec3(0.8f));
        jade::Baker baker(ctx);
        const auto baked = baker.bake(box, m, jade::BakeSettings::preset(jade::Quality::Draft));
        jade::Renderer renderer(ctx);
        renderer.set_mesh(box, baked.tm);
        renderer.set_material(m);
        const auto camera = jade::Camera::framing(box.bbox_min, box.bbox_max);
        jade::RenderSettings s;
        s.width = s.height = 32;
        for (auto mode : {jade::ShadingMode::Lambert, jade::ShadingMode::Curvature, jade::ShadingMode::Tm,
                          jade::ShadingMode::TmFalseColor}) {
            s.mode = mode;
            renderer.render(camera, jade::default_lights(camera), s);
        }
    }
    EXPECT_NE(log.find("synchronization validation on"), std::string::npos) << log;
    EXPECT_EQ(log.find("jade: vulkan validation"), std::string::npos) << log;
}

}  // namespace
