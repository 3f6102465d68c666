#include "gpu/texel_view.hpp"

#include "gpu/buffer.hpp"
#include "gpu/context.hpp"

#include <string>

namespace jade::gpu {

TexelView::TexelView(Context& ctx, const Buffer& buffer, VkFormat format, uint32_t texel_bytes, const char* name)
    : TexelView(ctx, buffer, format, texel_bytes, name, 0, buffer.size())
{
}

TexelView::TexelView(Context& ctx, const Buffer& buffer, VkFormat format, uint32_t texel_bytes, const char* name,
                     VkDeviceSize offset, VkDeviceSize bytes)
{
    const VkDeviceSize texels = bytes / texel_bytes;
    if (texels > ctx.limits().maxTexelBufferElements)
        throw Error(std::string(name) + ": " + std::to_string(texels) +
                    " texels exceed the device's maxTexelBufferElements (" +
                    std::to_string(ctx.limits().maxTexelBufferElements) + ")");
    VkBufferViewCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    ci.buffer = buffer.handle();
    ci.format = format;
    ci.offset = offset;
    ci.range = texels * texel_bytes;
    VkBufferView v;
    check(vkCreateBufferView(ctx.device(), &ci, nullptr, &v), (std::string("vkCreateBufferView ") + name).c_str());
    view_ = OwnedBufferView(ctx.device(), v);
    ctx.set_name(v, VK_OBJECT_TYPE_BUFFER_VIEW, name);
}

}  // namespace jade::gpu
