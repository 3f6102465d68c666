// shading/renderer_dev.cpp - the study knobs and introspection of jade/dev/renderer.hpp, which
// read a Renderer's Impl (shading/renderer_impl.hpp).
#include "shading/renderer_impl.hpp"

namespace jade {

// The introspection of jade/dev/renderer.hpp.
struct dev::RendererAccess {
    static Renderer::Impl& impl(const Renderer& renderer) { return *renderer.impl_; }
};

namespace dev {

const RendererStudy& study_of(const RendererOptions& options)
{
    static const RendererStudy defaults;
    return options.study ? *options.study : defaults;
}

void set_study(RendererOptions& options, const RendererStudy& study)
{
    options.study = std::make_shared<const RendererStudy>(study);
}

ShadingInputs shading_inputs(Renderer& renderer, const Camera& camera, std::span<const Light> lights,
                             const RenderSettings& settings)
{
    return RendererAccess::impl(renderer).shading_inputs(camera, lights, settings);
}

TmEvaluation tm_evaluation(const Renderer& renderer) { return RendererAccess::impl(renderer).evaluation; }
LightPathSampling light_path(const Renderer& renderer) { return RendererAccess::impl(renderer).light_path; }
const LutLayout& lut_layout(const Renderer& renderer) { return RendererAccess::impl(renderer).lut->layout(); }

std::vector<float> read_lut(Renderer& renderer)
{
    auto& m = RendererAccess::impl(renderer);
    return m.lut->read(m.ctx);
}

const std::vector<float>& curvature(const Renderer& renderer) { return RendererAccess::impl(renderer).curvature; }

double curvature_scale(const Renderer& renderer)
{
    const auto& m = RendererAccess::impl(renderer);
    if (!m.material) throw Error("dev::curvature_scale: no material (call set_material first)");
    return shading::CurvatureLut::length_scale(*m.material);
}

}  // namespace dev
}  // namespace jade
