// gpu/release_queue.cpp - see release_queue.hpp.
#include "gpu/release_queue.hpp"

namespace jade::gpu {

OwnedFence ReleaseQueue::take_fence()
{
    if (!spare_fences_.empty()) {
        OwnedFence f = std::move(spare_fences_.back());
        spare_fences_.pop_back();
        return f;
    }
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence f;
    check(vkCreateFence(device_, &fci, nullptr, &f), "vkCreateFence");
    return OwnedFence(device_, f);
}

void ReleaseQueue::release(std::vector<std::shared_ptr<void>> owners)
{
    collect();
    if (owners.empty()) return;
    Batch batch{take_fence(), std::move(owners)};
    // No batches, only the fence: it signals when all earlier submissions to the queue are done.
    check(vkQueueSubmit2(queue_, 0, nullptr, batch.fence), "vkQueueSubmit2 (release fence)");
    batches_.push_back(std::move(batch));
    if (wait_at_once_) destroy_all();
}

void ReleaseQueue::collect()
{
    // Fences of one queue signal in submission order, so the first unsignalled one ends the scan.
    while (!batches_.empty()) {
        VkFence f = batches_.front().fence;
        const VkResult status = vkGetFenceStatus(device_, f);
        if (status == VK_NOT_READY) return;
        check(status, "vkGetFenceStatus (release fence)");
        batches_.front().owners.clear();
        check(vkResetFences(device_, 1, &f), "vkResetFences");
        spare_fences_.push_back(std::move(batches_.front().fence));
        batches_.pop_front();
    }
}

void ReleaseQueue::destroy_all()
{
    while (!batches_.empty()) {
        VkFence f = batches_.front().fence;
        // A lost device signals nothing: drop the objects anyway rather than hang.
        vkWaitForFences(device_, 1, &f, VK_TRUE, UINT64_MAX);
        batches_.pop_front();
    }
    spare_fences_.clear();
}

}  // namespace jade::gpu
