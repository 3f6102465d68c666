// shading/lut.hpp - the two shading look-up tables as GPU textures.
//
//   TranslucencyLut  f(cos θ, t) of jade/dev/lut.hpp, R32_SFLOAT, built on the GPU by
//                    shaders/lut_build.comp (parameterisation: jade::LutLayout); mesh.frag
//                    reads the same texels in R16_UNORM for the sampler of a GPU, or (only
//                    with TmEvaluation::Lut) repacked as one RGBA32F "quad" per cell (the 2×2
//                    texels around it) from a uniform texel buffer, interpolated bilinearly
//                    in the shader (docs/shading.md compares the paths).
//   CurvatureLut     D_c(cos θ, κ) per colour channel, RGBA32F (A = 1), built on the CPU in
//                    float64 with jade::curvature_lut_reference and uploaded.
// The curvature LUT is sampled with linear filtering and clamp-to-edge (make_lut_sampler). Both
// put cos θ = 0 on a texel centre, so at t = 0 (κ = 0) the kink of max(cos θ, 0) is exact.
#pragma once

#include "gpu/buffer.hpp"
#include "gpu/image.hpp"
#include "gpu/texel_view.hpp"

#include <jade/dev/lut.hpp>
#include <jade/material.hpp>
#include <jade/render.hpp>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace jade::gpu {
class Context;
}

namespace jade::shading {

/// Scale and bias that turn a coordinate s ∈ [0, 1] sitting on texel centres 0 … n − 1 into a
/// texture coordinate: (s·(n − 1) + ½)/n = s·scale + bias.
inline glm::vec2 texel_centre_map(uint32_t n) { return {float(n - 1) / float(n), 0.5f / float(n)}; }

class TranslucencyLut {
public:
    /// Builds the LUT on the GPU (one submission) and leaves it in use::kSampled. Throws
    /// jade::Error for a bad size or a device that cannot filter R32_SFLOAT linearly.
    TranslucencyLut(gpu::Context& ctx, const LutLayout& layout);

    const LutLayout& layout() const { return layout_; }
    const gpu::Image& image() const { return image_; }
    /// Packs the quads (TmEvaluation::Lut, the only path that reads them; ~3.75 MiB at the
    /// default size) from the image's texels, once: later calls return at once. Thread-safe.
    void build_quads(gpu::Context& ctx);
    /// The quads: (W − 1) × (H − 1) RGBA32F texels; cell (i, j), at index j·(W − 1) + i, holds
    /// image texels (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1). Before build_quads, one
    /// zero texel: the descriptor of a draw that never reads them.
    const gpu::TexelView& quads() const { return quads_built_ ? quads_view_ : no_quads_view_; }
    /// The same texels as R16_UNORM, for a linearly filtering sampler (TmEvaluation::LutFiltered).
    const gpu::Image& filtered() const { return filtered_; }
    /// What mesh.frag indexes the quads with: column x = cos θ·m.x + m.x ∈ [0, W − 1],
    /// m.y = W − 1 quads a row, row y = (t/t_max)^¼·m.z ∈ [0, H − 1], m.w = H − 2 the last.
    glm::vec4 shader_map() const;
    /// Reads the texels back (width × height floats, row-major, row j = variance j).
    std::vector<float> read(gpu::Context& ctx);

private:
    LutLayout layout_;
    gpu::Image image_;
    std::mutex quads_mutex_;
    std::atomic<bool> quads_built_ = false;
    gpu::Buffer quads_, no_quads_;
    gpu::TexelView quads_view_, no_quads_view_;  // destroyed before the buffers
    gpu::Image filtered_;
};

/// The translucency LUT of `layout` on `ctx`'s device, shared by every Renderer of that device
/// and layout while one of them holds it: built (one GPU submission) when none does, freed with
/// the last holder. The LUT depends on nothing else (not on the material), so a scene of many
/// objects builds and keeps one. Thread-safe.
std::shared_ptr<TranslucencyLut> shared_translucency_lut(gpu::Context& ctx, const LutLayout& layout);

class CurvatureLut {
public:
    /// Evaluates D for every texel on all CPU threads, uploads it, leaves it in use::kSampled.
    CurvatureLut(gpu::Context& ctx, const Material& material, uint32_t width, uint32_t height);

    /// The length d̄ (mesh units) the curvature axis is scaled by: the mean over the channels of
    /// the profile's median radius (cdf = ½). Rows are at κ·d̄ = v/(1 − v), v = j/(H − 1).
    static double length_scale(const Material& material);
    /// Texel values, width × height RGBA, row j at κ·d̄ = v_j/(1 − v_j).
    static std::vector<glm::vec4> evaluate(const Material& material, uint32_t width, uint32_t height);

    double scale() const { return scale_; }
    const gpu::Image& image() const { return image_; }
    /// u = cos θ·x + y, v = (κd̄ / (1 + κd̄))·z + w.
    glm::vec4 shader_map() const;

private:
    double scale_ = 1.0;
    gpu::Image image_;
};

/// Linear filtering, clamp-to-edge: what both LUTs are sampled with.
gpu::OwnedSampler make_lut_sampler(const gpu::Context& ctx);

}  // namespace jade::shading
