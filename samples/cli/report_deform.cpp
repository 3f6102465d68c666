// report_deform.cpp - the deformation steps of `jade report`: a twisting mesh re-baked every
// frame by refitting both trees (DynamicBake) and by amortised re-bakes, each frame against a
// from-scratch bake of the same deformed mesh (new trees: the rebuild). Rows:
//   deform_ao  absolute AO error     (value: rebuild | refit | 1/N; GPU = bake per frame)
//   deform_tm  relative t_m error    (same runs; each mode runs once and gives both rows)
// Errors: RMS = mean over frames of the per-frame RMS, p99 not measured, max over all frames.
#include "deform_sweep.hpp"
#include "report.hpp"

#include <memory>

namespace jade::cli::report {

void add_deform_steps(Session& s, MeshState& st, std::vector<Step>& steps)
{
    struct Shared {
        std::unique_ptr<DeformSweep> sweep;
        SweepStats last;
        Material material;
        BakeSettings settings;
    };
    auto shared = std::make_shared<Shared>();
    steps.push_back({"deform: twist frames and their from-scratch bakes",
                     [&s, &st, shared] {
        shared->material = st.materials.front().material;
        shared->settings = BakeSettings::preset(Quality::Default);
        shared->settings.ao.rays = 32;
        ProceduralDeformer twist = ProceduralDeformer::fit(DeformerKind::Twist, st.mesh, 1);
        twist.period = 2.0f;
        shared->sweep = std::make_unique<DeformSweep>(s.context, s.baker, st.mesh, shared->material, shared->settings,
                                                      twist, s.plan.deform_frames, 1.0 / 15.0);
        Row r{st.label,
              "deform_tm",
              "rebuild",
              "from scratch (" + st.materials.front().label + ")",
              shared->sweep->rebuild_gpu_ms(),
              shared->sweep->rebuild_wall_ms(),
              {0, kNaN, 0},
              strf("%u frames of a twist at 15 fps, 32 AO rays, default ε; the reference of the rows below",
                   s.plan.deform_frames)};
        return r;
                     }});
    auto mode = [&](const std::string& value, Amortisation a) {
        steps.push_back({"deform: " + value,
                         [&st, shared, value, a] {
            shared->last = shared->sweep->run(a);
            const SweepStats& m = shared->last;
            Row r{st.label,
                  "deform_ao",
                  value,
                  (value == "refit" ? "refit" : "amortised") + std::string(" (") + st.materials.front().label + ")",
                  m.bake(),
                  kNaN,
                  {m.error.ao_rms, kNaN, m.error.ao_max},
                  strf("AO %.1f ms, t_m %.1f ms, refits %.2f ms per frame", m.ao, m.tm, m.refit)};
            return r;
                         }});
        steps.push_back({"deform: " + value + " (t_m)", [&st, shared, value] {
                             const SweepStats& m = shared->last;
                             return Row{st.label,
                                        "deform_tm",
                                        value,
                                        (value == "refit" ? "refit" : "amortised") + std::string(" (") +
                                            st.materials.front().label + ")",
                                        m.bake(),
                                        kNaN,
                                        {m.error.tm_rms, kNaN, m.error.tm_max},
                                        ""};
                         }});
    };
    mode("refit", {});
    for (uint32_t n : s.plan.deform_slices) mode("1/" + std::to_string(n), {n, n});
    steps.push_back({"deform: release", [shared] {
                         shared->sweep.reset();
                         return Row{};
                     }});
}

}  // namespace jade::cli::report
