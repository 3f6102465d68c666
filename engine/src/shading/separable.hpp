// shading/separable.hpp - the Separable mode's own targets and passes (Jimenez et al. 2015,
// "Separable Subsurface Scattering"; reference code iryoku/separable-sss, followed, not copied):
//   1. the mesh pass (mesh.frag, MODE kSeparable) writes the specular light into the caller's
//      colour target and the diffuse light (k_d applied before the blur, as the reference
//      demo's pre-scatter texturing; the same as after it for Jade's constant k_d) plus
//      SSSSTransmittance's light, with the linear depth in alpha, into an irradiance target of
//      its own (RGBA32F, as multisampled as the draw, resolved: averaged);
//   2. a horizontal 1-D pass of the kernel (jade/dev/separable.hpp) into a second image;
//   3. a vertical pass added (blended ONE + ONE, alpha kept) to the caller's single-sample image
//      (the resolve, or the colour when samples = 1).
// The Burley mode (screen-space Burley diffusion as HDRP, jade/dev/burley_diffusion.hpp) shares step 1
// and replaces 2 and 3 by one pass of importance-sampled taps (burley_blur.frag), added likewise.
// Only translucent pixels pay: the passes draw a fullscreen triangle clipped by a scissor to the
// mesh's bounding box on screen, and discard pixels whose irradiance alpha (the depth) is 0 at
// once (the stencil's equivalent; lavapipe shades whole 4×4 blocks, so the scissor is what saves
// there).
#pragma once

#include "gpu/buffer.hpp"
#include "gpu/image.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/vk.hpp"

#include <jade/material.hpp>
#include <jade/render.hpp>

#include "shading_interface.h"

#include <array>
#include <cstdint>
#include <map>
#include <optional>

namespace jade::gpu {
class Context;
}

namespace jade::shading {

static_assert(sizeof(SeparableData) <= sizeof(FrameData), "the frame constants stand in for SeparableData");

/// The irradiance target's format: alpha holds the linear depth, at full precision.
inline constexpr VkFormat kSeparableIrradianceFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

/// The kernel for `taps` and the transmittance table of the material, as the shaders read them.
/// The table spans d ∈ [0, reach], reach the widest channel's radius_for_tail(1e-4), at
/// d_i = reach · (i / (STEPS − 1))² (the narrowest channel's steep start needs the dense steps).
/// With the Burley mode's shapes and `burley_samples` radii (jade/dev/burley_diffusion.hpp).
SeparableData separable_data(const Material& material, uint32_t taps, uint32_t burley_samples);

class SeparablePasses {
public:
    /// Makes nothing: a renderer that never draws the separable mode pays nothing for it.
    explicit SeparablePasses(gpu::Context& ctx) : ctx_(ctx) {}

    /// What every mesh pipeline binds at binding 6: the constants, once a separable draw made
    /// them; before that `stand_in`, any uniform buffer of at least sizeof(SeparableData) bytes
    /// (the renderer's frame constants), which only the separable mode would read.
    const gpu::Buffer& data_or(const gpu::Buffer& stand_in) const { return data_ ? data_ : stand_in; }

    /// Before the mesh pass of a separable draw, outside rendering: the targets for this size and
    /// sample count, the constants for this material and tap count (vkCmdUpdateBuffer, guarded
    /// like the frame constants), the irradiance target made a colour attachment (discarded).
    /// Returns that target as the mesh pass's second colour attachment (cleared to 0). Throws
    /// jade::Error for a tap count other than 11, 17, 25, and for a multisampled target that is
    /// kept for more draws (RenderTarget::keep: its multisampled colour would lack the blurred
    /// light, which goes to the resolve only).
    VkRenderingAttachmentInfo prepare(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s,
                                      const Material& material);
    /// After the mesh pass: the two blur passes, the second added into `t`'s single-sample image,
    /// both within the screen bounds of the mesh's box [lo, hi] (view_proj: the draw's).
    void record_blur(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s, VkFormat color_format,
                     const Camera& camera, const glm::mat4& view_proj, glm::vec3 lo, glm::vec3 hi);

private:
    VkRenderingAttachmentInfo irradiance_attachment() const;
    enum class Pass : uint32_t { Horizontal = 0, Vertical = 1, Burley = 2 };
    /// count: the separable passes' taps, the Burley pass's samples.
    const gpu::GraphicsPipeline& pass_pipeline(Pass pass, uint32_t count, VkFormat format);

    gpu::Context& ctx_;
    gpu::OwnedSampler sampler_;
    gpu::Buffer data_;
    SeparableData constants_{};
    std::optional<std::array<ChannelProfile, 3>> profiles_;  // what constants_ were made for
    uint32_t taps_ = 0, samples_made_ = 0;
    uint32_t width_ = 0, height_ = 0, samples_ = 0;
    gpu::Image irradiance_msaa_, irradiance_, horizontal_;
    std::map<uint64_t, gpu::GraphicsPipeline> pipelines_;
};

/// The mesh's bounding box [lo, hi] on screen (pixels, clamped to the image, one pixel of
/// margin), or the whole image when a corner is behind the eye.
VkRect2D screen_bounds(const glm::mat4& view_proj, glm::vec3 lo, glm::vec3 hi, uint32_t width, uint32_t height);

}  // namespace jade::shading
