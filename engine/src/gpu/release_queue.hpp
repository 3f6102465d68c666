// gpu/release_queue.hpp - objects released once the GPU is done with them, without waiting.
//
// A Renderer's old vertex buffers may still be read by draws the host recorded and submitted.
// Waiting for the device to be idle would stall every queue of a host's device. Instead the
// objects go into a batch with a fence, submitted to Jade's queue in an otherwise empty
// vkQueueSubmit2: a fence signal operation of a queue submission command covers every command
// submitted to that queue before it (Vulkan spec, "Fences": the first synchronization scope
// includes all commands that occur earlier in submission order). Later calls poll the fences
// (vkGetFenceStatus, never a wait) and free the batches that are done; destroy_all() waits for
// what is left, when the Context goes. On Jade's own device (no host to stall) release() waits
// for its fence at once, so that objects go as promptly and predictably as they are let go of.
//
// The contract this gives callers: release an object after every command buffer that uses it
// was submitted to the Context's queue (or never will be); the release itself does not block.
#pragma once

#include "gpu/vk.hpp"

#include <deque>
#include <memory>
#include <vector>

namespace jade::gpu {

using OwnedFence = Owned<VkFence, vkDestroyFence>;  // also the Context's own submission fence

class ReleaseQueue {
public:
    ReleaseQueue() = default;
    /// `wait_at_once`: release() waits for its fence (Jade's own device, not a host's).
    ReleaseQueue(VkDevice device, VkQueue queue, bool wait_at_once)
        : device_(device), queue_(queue), wait_at_once_(wait_at_once)
    {
    }
    ReleaseQueue(const ReleaseQueue&) = delete;
    ReleaseQueue& operator=(const ReleaseQueue&) = delete;
    ReleaseQueue(ReleaseQueue&&) = default;
    ReleaseQueue& operator=(ReleaseQueue&&) = default;

    /// Keeps `owners` alive until the GPU has finished everything submitted to the queue so far
    /// (submits the batch's fence now), then drops them in a later collect() or destroy_all().
    void release(std::vector<std::shared_ptr<void>> owners);
    /// Drops the batches whose fence has signalled, oldest first; never waits.
    void collect();
    /// Waits for every batch's fence, then drops them all (the Context's destructor).
    void destroy_all();
    /// Batches not yet dropped (tests).
    size_t pending() const { return batches_.size(); }

private:
    struct Batch {
        OwnedFence fence;
        std::vector<std::shared_ptr<void>> owners;
    };
    OwnedFence take_fence();

    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    bool wait_at_once_ = false;
    std::deque<Batch> batches_;
    std::vector<OwnedFence> spare_fences_;  // reset, for the next batch
};

}  // namespace jade::gpu
