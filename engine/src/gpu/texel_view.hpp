// gpu/texel_view.hpp - a buffer seen as an array of texels (a uniform texel buffer).
//
// Read-only data that compute passes fetch many times (BVH nodes, triangles, t_m sources and
// clusters) is read through texel views, not storage-buffer loads: lavapipe turns a texel
// fetch into one SIMD gather, but a storage-buffer load into a per-lane loop of bounds-checked
// scalar loads - a 4-component fetch measured 3-4x cheaper (docs/lavapipe.md). On desktop
// GPUs texel fetches go through the texture cache, which suits these reads as well.
// Integer data must use an integer format (RGBA32UI): a float format may flush the bit
// patterns of small integers (denormals) to zero. Shaders bitcast with uintBitsToFloat.
#pragma once

#include "gpu/vk.hpp"

namespace jade::gpu {

class Buffer;
class Context;

using OwnedBufferView = Owned<VkBufferView, vkDestroyBufferView>;

class TexelView {
public:
    TexelView() = default;
    /// Views `buffer` (created with VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) as texels of
    /// `format`, `texel_bytes` each. Throws jade::Error when the buffer holds more texels than
    /// the device's maxTexelBufferElements.
    TexelView(Context& ctx, const Buffer& buffer, VkFormat format, uint32_t texel_bytes, const char* name);
    /// Views `bytes` of `buffer` from byte `offset` (a multiple of minTexelBufferOffsetAlignment).
    TexelView(Context& ctx, const Buffer& buffer, VkFormat format, uint32_t texel_bytes, const char* name,
              VkDeviceSize offset, VkDeviceSize bytes);

    VkBufferView handle() const { return view_; }
    explicit operator bool() const { return bool(view_); }

private:
    OwnedBufferView view_;
};

}  // namespace jade::gpu
