// deform_sweep.hpp - what `jade bench deform` and `jade report` share: a procedural deformation
// played frame by frame through MeshDeformer + DynamicBake (+ optionally a draw), full or
// amortised, with each frame's result compared against a from-scratch bake of that frame.
#pragma once

#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/deform.hpp>
#include <jade/render.hpp>

#include <memory>
#include <vector>

namespace jade::cli {

/// Error of a re-bake against the from-scratch bake of the same deformed frame.
struct FrameError {
    double ao_rms = 0, ao_max = 0;  ///< absolute (A_o ∈ [0, 1])
    double tm_rms = 0, tm_max = 0;  ///< relative, over vertices and colour channels
};

/// GPU milliseconds per frame by stage, and the error, over the frames measured.
struct SweepStats {
    double deform = 0, normals = 0, refit = 0, ao = 0, tm = 0, draw = 0;
    FrameError error;  ///< mean of the per-frame RMS values, max of the per-frame maxima
    uint32_t frames = 0;
    double bake() const { return refit + ao + tm; }
    double total() const { return deform + normals + bake() + draw; }
};

class DeformSweep {
public:
    /// Deforms `rest` with `deformer` at t = 0, step, 2·step, ... (`frames` frames) and bakes each
    /// frame from scratch (Baker::bake, the rest pose's AO distances): the reference of run().
    DeformSweep(Context& context, Baker& baker, const PreparedMesh& rest, const Material& material,
                const BakeSettings& settings, const ProceduralDeformer& deformer, uint32_t frames, double step);

    /// Plays the frames with a DynamicBake under `amortisation` (and draws each frame with
    /// `renderer` when given, at `size`²). An amortised mode's first frame is a full re-bake and
    /// is left out of the averages.
    SweepStats run(const Amortisation& amortisation, Renderer* renderer = nullptr, uint32_t size = 512);

    /// GPU time of the from-scratch bakes (new BVH and cluster tree per frame), mean per frame;
    /// wall includes the CPU tree builds.
    double rebuild_gpu_ms() const { return rebuild_gpu_ms_; }
    double rebuild_wall_ms() const { return rebuild_wall_ms_; }

private:
    const PreparedMesh& rest_;
    const Material& material_;
    ProceduralDeformer params_;
    double step_;
    MeshDeformer deformer_;
    DynamicBake rebake_;
    std::vector<BakeResult> reference_;
    std::vector<Camera> cameras_;
    double rebuild_gpu_ms_ = 0, rebuild_wall_ms_ = 0;
};

}  // namespace jade::cli
