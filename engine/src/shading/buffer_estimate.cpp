// shading/buffer_estimate.cpp - the renderer's and the LUT's buffers, as they allocate them.
#include <jade/dev/lut.hpp>
#include "shading/buffer_estimate.hpp"

#include "gpu/buffer.hpp"
#include "shading/transmission_table.hpp"

#include <glm/vec4.hpp>

#include <algorithm>
#include <cstdint>

namespace jade::shading {
namespace {

uint64_t bytes(uint64_t b) { return std::max<uint64_t>(gpu::kMinBufferBytes, b); }

}  // namespace

std::vector<dev::BufferEstimate> estimate_draw_buffers(size_t n, size_t tris, const Material& material)
{
    return {{"mesh vertices", bytes(kRendererVertexBytes * n)},
            {"mesh indices", bytes(3 * sizeof(uint32_t) * tris)},
            {"frame data", bytes(kRendererFrameDataBytes)},
            {"transmission table", TransmissionTable::bytes(material.transmission)},
            // A 1×1 RGBA32F image until a curvature LUT is set (the tm modes never set one).
            {"curvature LUT placeholder (image)", sizeof(glm::vec4), true}};
}

std::vector<dev::BufferEstimate> estimate_lut_buffers(const LutLayout& l, TmEvaluation evaluation)
{
    // One RGBA32F quad per cell of the R32F image (TranslucencyLut::build_quads), or the one
    // texel bound in their place.
    const uint64_t cells = evaluation == TmEvaluation::Lut ? uint64_t(l.width - 1) * (l.height - 1) : 1;
    return {{"translucency LUT quads", bytes(sizeof(glm::vec4) * cells)},
            {"translucency LUT (image)", uint64_t(l.width) * l.height * sizeof(float), true},
            {"translucency LUT, 16 bit (image)", uint64_t(l.width) * l.height * sizeof(uint16_t), true}};
}

}  // namespace jade::shading
