// fidelity_modes.hpp - the columns of `jade fidelity`: which shading modes (and peers) it scores,
// with or without shadows, and the Markdown tables it writes (docs/fidelity.md, docs/peers.md).
#pragma once

#include "args.hpp"

#include <jade/render.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace jade::cli {

/// A column of the comparison: a shading mode as the comparison draws it. A mode added to the
/// renderer is one line here; everything below (console, JSON, Markdown, --modes) follows.
struct Mode {
    const char* name;
    ShadingMode mode;
    bool transmission;              // Tm: the default's transmission and boundary terms (else the poster's model)
    float filament_thickness = -1;  // Filament: a constant thickness (no hand-made map), or the baked one
    const char* what;               // for --help and the tables' notes
};
inline constexpr Mode kModes[] = {
    {"lambert", ShadingMode::Lambert, false, -1, "Lambert"},
    {"curvature", ShadingMode::Curvature, false, -1, "curvature model (Kubo et al. 2010 / pre-integrated)"},
    {"tm", ShadingMode::Tm, false, -1, "the poster's t_m model alone"},
    {"default", ShadingMode::Tm, true, -1, "Jade's default: t_m with transmission and boundary terms"},
    {"filament", ShadingMode::Filament, false, -1, "Filament's subsurface model fed Jade's baked thickness"},
    {"filament-flat", ShadingMode::Filament, false, 0.5f, "Filament's model without a thickness map (0.5)"},
    {"separable", ShadingMode::Separable, true, -1,
     "Jimenez et al.'s separable SSS (17 taps), kernel from the profile"},
    {"burley", ShadingMode::Burley, true, -1, "HDRP's screen-space Burley diffusion (40 samples)"},
};

/// --modes LIST: names of kModes, in the order given (default: all, in kModes' order).
std::vector<const Mode*> modes_from_args(const Args& args);
/// --shadows on | off | both (--no-shadows: off): the shadow states each mode is scored in.
std::vector<bool> shadow_states(const Args& args);
/// The column's name and JSON key: MODE, or MODE/noshadow.
std::string column(const Mode& m, bool shadows);
/// The column in a file name: SCENE__MODE.png, SCENE__MODE_noshadow.png.
std::string name_for_file(std::string column);
/// Per scene and per light (mean masked FLIP; thin region's luminance over the path tracer's)
/// of every column, from `jade fidelity`'s JSON rows.
std::string fidelity_markdown(const nlohmann::json& rows, const std::vector<const Mode*>& modes,
                              const std::vector<bool>& shadows, const std::string& device);

}  // namespace jade::cli
