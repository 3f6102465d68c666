// shading/offscreen.hpp - what Renderer::render and SceneRenderer::render draw into when the
// host gives no target: a colour attachment (multisampled or not), its resolve, a D32 depth and
// a host-visible read-back buffer, kept while the size, sample count and format stay the same.
#pragma once

#include "gpu/buffer.hpp"
#include "gpu/image.hpp"

#include <jade/render.hpp>

#include <string>
#include <vector>

namespace jade::shading {

class OffscreenTarget {
public:
    /// Remakes the images and the read-back buffer (named "<name> colour", …) when the settings'
    /// size or sample count, or `color_format`, differ from the last call's.
    void ensure(gpu::Context& ctx, const RenderSettings& s, VkFormat color_format, const std::string& name);
    /// Before the draws: the old contents are discarded (every draw clears or loads what the
    /// previous one in this submission wrote), after the previous frame's read-back copy.
    void begin(VkCommandBuffer cmd);
    /// The views for Renderer::record; `load`/`keep` as RenderTarget's.
    RenderTarget target(bool load = false, bool keep = false) const;
    /// After the draws: the resolved (or single-sampled) colour into the read-back buffer.
    void copy_out(VkCommandBuffer cmd);
    /// The read-back as linear RGBA floats, after the submission with copy_out() completed.
    std::vector<float> read_rgba() const;

private:
    uint32_t width_ = 0, height_ = 0, samples_ = 0;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    gpu::Image color_, resolve_, depth_;
    gpu::Buffer readback_;
};

}  // namespace jade::shading
