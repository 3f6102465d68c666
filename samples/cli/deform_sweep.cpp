// deform_sweep.cpp - see deform_sweep.hpp.
#include "deform_sweep.hpp"

#include <algorithm>
#include <cmath>

namespace jade::cli {
namespace {

FrameError compare(const BakeResult& got, const BakeResult& ref)
{
    FrameError e;
    const size_t n = ref.ao.size();
    for (size_t i = 0; i < n; ++i) {
        const double d = double(got.ao[i]) - double(ref.ao[i]);
        e.ao_rms += d * d, e.ao_max = std::max(e.ao_max, std::abs(d));
        for (int c = 0; c < 3; ++c) {
            const double r = (double(got.tm[i][c]) - double(ref.tm[i][c])) / std::max(double(ref.tm[i][c]), 1e-12);
            e.tm_rms += r * r, e.tm_max = std::max(e.tm_max, std::abs(r));
        }
    }
    e.ao_rms = std::sqrt(e.ao_rms / double(n));
    e.tm_rms = std::sqrt(e.tm_rms / (3.0 * double(n)));
    return e;
}

}  // namespace

DeformSweep::DeformSweep(Context& context, Baker& baker, const PreparedMesh& rest, const Material& material,
                         const BakeSettings& settings, const ProceduralDeformer& deformer, uint32_t frames, double step)
    : rest_(rest), material_(material), params_(deformer), step_(step), deformer_(context, rest),
      rebake_(baker, rest, material, settings)
{
    for (uint32_t f = 0; f < frames; ++f) {
        deformer_.deform(params_, step_ * f);
        PreparedMesh deformed = deformed_mesh(rest, deformer_.read());
        deformed.diagonal = rest.diagonal;  // DynamicBake keeps the rest pose's AO distances
        reference_.push_back(baker.bake(deformed, material, settings));
        rebuild_gpu_ms_ += reference_.back().timings.gpu_total_ms / frames;
        rebuild_wall_ms_ += reference_.back().timings.wall_ms / frames;
        cameras_.push_back(Camera::framing(deformed.bbox_min, deformed.bbox_max));
    }
}

SweepStats DeformSweep::run(const Amortisation& amortisation, Renderer* renderer, uint32_t size)
{
    rebake_.set_amortisation(amortisation);  // the first frame re-bakes everything
    const bool amortised = amortisation.ao_slices * amortisation.tm_slices > 1;
    RenderSettings render_settings;
    render_settings.width = render_settings.height = size;
    SweepStats st;
    for (uint32_t f = 0; f < reference_.size(); ++f) {
        const DeformTimings dt = deformer_.deform(params_, step_ * f);
        const MeshDeformer::Buffers d = deformer_.buffers();
        const BakeResult r = rebake_.bake(d.positions, d.normals, d.areas);
        double draw_ms = 0;
        if (renderer) {
            renderer->set_mesh(deformed_mesh(rest_, deformer_.read()), r);
            draw_ms = renderer->render(cameras_[f], default_lights(cameras_[f]), render_settings).gpu_ms;
        }
        if (f == 0 && amortised) continue;  // measure the steady state
        st.deform += dt.deform_ms, st.normals += dt.normals_ms, st.draw += draw_ms;
        for (const auto& [stage, ms] : r.timings.gpu_stages) {
            if (stage == "BVH refit")
                st.refit += ms;
            else if (stage == "ao")
                st.ao += ms;
            else
                st.tm += ms;
        }
        const FrameError e = compare(r, reference_[f]);
        st.error.ao_rms += e.ao_rms, st.error.tm_rms += e.tm_rms;
        st.error.ao_max = std::max(st.error.ao_max, e.ao_max), st.error.tm_max = std::max(st.error.tm_max, e.tm_max);
        ++st.frames;
    }
    const double n = std::max(1u, st.frames);
    st.deform /= n, st.normals /= n, st.refit /= n, st.ao /= n, st.tm /= n, st.draw /= n;
    st.error.ao_rms /= n, st.error.tm_rms /= n;
    return st;
}

}  // namespace jade::cli
