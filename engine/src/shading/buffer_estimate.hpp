// shading/buffer_estimate.hpp - what the renderer allocates on the GPU, before it exists (for
// plan_scene, jade/scene.hpp). Private to the engine.
#pragma once

#include <jade/dev/lut.hpp>
#include <jade/dev/renderer.hpp>  // TmEvaluation
#include <jade/render.hpp>
#include <jade/dev/scene.hpp>  // BufferEstimate

#include <cstddef>
#include <cstdint>
#include <vector>

namespace jade::shading {

/// What the renderer keeps per vertex (position, normal, t_m, curvature, thickness, scattering
/// normal, normal spread: floats) and its per-draw constants with 64 lights, in bytes: for
/// memory plans (jade/scene.hpp).
inline constexpr uint64_t kRendererVertexBytes = 68;
inline constexpr uint64_t kRendererFrameDataBytes = 3456;

/// What one Renderer holds of its own while it draws a mesh of `vertices` bake vertices and
/// `triangles` triangles (shading/renderer.cpp: its Vertex and FrameData, whose sizes it
/// asserts against kRendererVertexBytes and kRendererFrameDataBytes). Exact.
/// `material`'s transmission sets the size of its attenuation table (shading/transmission_table.hpp).
std::vector<dev::BufferEstimate> estimate_draw_buffers(size_t vertices, size_t triangles, const Material& material);

/// The translucency LUT of `layout` (shading/lut.cpp, TranslucencyLut), which every Renderer of
/// a device shares: its image, the image's 16-bit copy and its quads buffer, which holds the
/// quads only for TmEvaluation::Lut (Auto never resolves to it), else one texel. Exact.
std::vector<dev::BufferEstimate> estimate_lut_buffers(const LutLayout& layout, TmEvaluation evaluation);

}  // namespace jade::shading
