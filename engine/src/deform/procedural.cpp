// deform/procedural.cpp - the procedural deformers' parameters (their per-vertex work is
// shaders/deform_procedural.comp, driven by deform/mesh_deformer.cpp).
#include <jade/deform.hpp>
#include <jade/dev/deform.hpp>
#include <jade/dev/names.hpp>
#include <jade/error.hpp>

#include <cmath>
#include <string>

namespace jade {

namespace {
constexpr std::string_view kNames[] = {"bend", "twist", "squash", "wave"};
}

std::string_view dev::deformer_name(DeformerKind kind) { return kNames[uint32_t(kind) % 4]; }

DeformerKind dev::parse_deformer(std::string_view name)
{
    for (uint32_t k = 0; k < 4; ++k)
        if (name == kNames[k]) return DeformerKind(k);
    throw Error("deformer '" + std::string(name) + "' is not one of bend, twist, squash, wave");
}

ProceduralDeformer ProceduralDeformer::fit(DeformerKind kind, const PreparedMesh& mesh, uint32_t axis)
{
    if (axis > 2) throw Error("deformer axis " + std::to_string(axis) + " is not 0 (x), 1 (y) or 2 (z)");
    ProceduralDeformer d;
    d.kind = kind;
    d.axis = axis;
    d.origin = 0.5f * (mesh.bbox_min + mesh.bbox_max);
    d.origin[int(axis)] = mesh.bbox_min[int(axis)];
    d.length = mesh.bbox_max[int(axis)] - mesh.bbox_min[int(axis)];
    if (!(d.length > 0.0f)) d.length = mesh.diagonal > 0.0f ? mesh.diagonal : 1.0f;  // flat along the axis
    switch (kind) {
    case DeformerKind::Bend: d.amplitude = 0.8f; break;
    case DeformerKind::Twist: d.amplitude = 1.2f; break;
    case DeformerKind::Squash: d.amplitude = 0.25f; break;
    case DeformerKind::Wave: d.amplitude = 0.04f * d.length; break;
    }
    d.wavelength = 0.5f * d.length;
    return d;
}

void dev::validate_deformer(const ProceduralDeformer& d)
{
    auto bad = [&](const std::string& what) {
        throw Error(std::string(dev::deformer_name(d.kind)) + " deformer: " + what);
    };
    if (uint32_t(d.kind) > 3) bad("unknown kind " + std::to_string(uint32_t(d.kind)));
    if (d.axis > 2) bad("axis " + std::to_string(d.axis) + " is not 0 (x), 1 (y) or 2 (z)");
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(d.origin[c])) bad("origin is not finite");
    if (!(d.length > 0.0f) || !std::isfinite(d.length))
        bad("length " + std::to_string(d.length) + " must be positive and finite");
    if (!std::isfinite(d.amplitude)) bad("amplitude is not finite");
    if (d.kind == DeformerKind::Squash && !(std::abs(d.amplitude) < 1.0f))
        bad("squash amplitude " + std::to_string(d.amplitude) +
            " must be in (-1, 1) (the stretch factor 1 ± amplitude stays positive)");
    if (!(d.wavelength > 0.0f) || !std::isfinite(d.wavelength))
        bad("wavelength " + std::to_string(d.wavelength) + " must be positive and finite");
    if (!(d.period > 0.0f) || !std::isfinite(d.period))
        bad("period " + std::to_string(d.period) + " must be positive and finite");
}

}  // namespace jade
