// gpu/pipeline.hpp - the one way to make and bind a graphics pipeline (the graphics twin of
// gpu/kernel.hpp).
//
// A pipeline is a description with defaults that fit Jade's renderer: dynamic rendering (no
// render passes or framebuffers), one colour attachment in RGBA16F, depth D32 with LESS test
// and writes, 4× MSAA, back faces culled (meshes are counter-clockwise seen from outside),
// triangle lists, dynamic viewport and scissor, no blending. A fullscreen pass: no vertex
// attributes, depth_format VK_FORMAT_UNDEFINED, samples 1, cull none, `vkCmdDraw(cmd, 3, ...)`
// of shaders/fullscreen.vert; Blend::AddColor adds its colour to what the attachment holds. Bindings are push descriptors, as for compute
// kernels; push constants are visible to the vertex and fragment stages; specialisation
// constants 0, 1, ... go to both stages. `bind` sets pipeline, descriptors, push constants,
// viewport and scissor in one call, so a draw is `bind(...)` then `vkCmdDraw*`.
#pragma once

#include "gpu/kernel.hpp"
#include "gpu/vk.hpp"

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

namespace jade::gpu {

class Context;

/// One vertex attribute of the (single, interleaved) vertex buffer binding 0.
struct VertexAttribute {
    uint32_t location;
    VkFormat format;
    uint32_t offset;  ///< bytes from the start of the vertex
};

/// How a colour attachment combines what the fragment shader writes with what it holds.
enum class Blend : uint32_t {
    None = 0,      ///< replaced (opaque surfaces)
    AddColor = 1,  ///< rgb: source + destination; alpha: the destination's kept
};

struct GraphicsPipelineDesc {
    const char* name = "graphics";
    std::span<const uint32_t> vertex_spirv, fragment_spirv;

    // Attachments (must match the VkRenderingInfo the draw is recorded in).
    std::vector<VkFormat> color_formats{VK_FORMAT_R16G16B16A16_SFLOAT};
    VkFormat depth_format = VK_FORMAT_D32_SFLOAT;  ///< VK_FORMAT_UNDEFINED: no depth attachment
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;

    // Fixed-function state.
    bool depth_test = true, depth_write = true;
    VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
    VkCullModeFlags cull = VK_CULL_MODE_BACK_BIT;
    VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    /// The channels every colour attachment takes (VK_COLOR_COMPONENT_*_BIT); the rest keep
    /// what the attachment held.
    VkColorComponentFlags color_write_mask = 0xf;
    Blend blend = Blend::None;  ///< every colour attachment

    // Vertex input: one interleaved buffer at binding 0 (stride 0 and no attributes: none).
    uint32_t vertex_stride = 0;
    std::vector<VertexAttribute> attributes;

    // Resources.
    std::vector<VkDescriptorType> bindings;  ///< push-descriptor binding i has type bindings[i]
    uint32_t push_size = 0;                  ///< bytes, ≤ maxPushConstantsSize
    std::vector<uint32_t> constants;         ///< specialisation constants 0, 1, ... (32-bit each)
};

class GraphicsPipeline {
public:
    GraphicsPipeline() = default;
    GraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc);

    /// Binds the pipeline, pushes `bindings` and `push` (exactly push_size bytes), and sets the
    /// viewport and scissor to `extent`. Checks counts and sizes before recording.
    void bind(VkCommandBuffer cmd, VkExtent2D extent, const void* push, size_t push_bytes,
              std::initializer_list<Binding> bindings) const;
    template <class Push>
    void bind(VkCommandBuffer cmd, VkExtent2D extent, const Push& push, std::initializer_list<Binding> bindings) const
    {
        bind(cmd, extent, &push, sizeof(Push), bindings);
    }

    const char* name() const { return name_; }
    VkPipelineLayout layout() const { return layout_; }
    VkPipeline handle() const { return pipeline_; }

private:
    Context* ctx_ = nullptr;
    const char* name_ = "";
    std::vector<VkDescriptorType> bindings_;
    uint32_t push_size_ = 0;
    OwnedSetLayout set_layout_;  // destroyed after the layout and pipeline that use it
    OwnedPipelineLayout layout_;
    OwnedPipeline pipeline_;
};

}  // namespace jade::gpu
