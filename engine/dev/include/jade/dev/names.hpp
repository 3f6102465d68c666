// jade/dev/names.hpp - the names of the core's enums as the CLI's flags, reports and tests spell
// them, and their parsers (a host names its own settings). The dev enums are named next to them
// (jade/dev/renderer.hpp, jade/dev/scene.hpp). Declared for jade::dev, defined in jade::jade.
#pragma once

#include <jade/bake.hpp>
#include <jade/deform.hpp>
#include <jade/render.hpp>

#include <string_view>

namespace jade::dev {

/// "auto", "exact", "clustered", "grid"; parse_tm_method throws jade::Error on anything else.
const char* tm_method_name(TmMethod method);
TmMethod parse_tm_method(std::string_view name);

/// "draft", "default", "high"; parse_quality throws jade::Error on anything else.
const char* quality_name(Quality quality);
Quality parse_quality(std::string_view name);

/// "bend", "twist", "squash", "wave".
std::string_view deformer_name(DeformerKind kind);
/// The inverse of deformer_name; throws jade::Error listing the names.
DeformerKind parse_deformer(std::string_view name);

/// "lambert", "curvature", "tm", "tm-false-color", "filament", "separable", "burley".
std::string_view shading_mode_name(ShadingMode mode);
/// The inverse of shading_mode_name; throws jade::Error listing the names.
ShadingMode parse_shading_mode(std::string_view name);

/// "none", "reinhard", "aces"; throws jade::Error listing the names.
ToneMap parse_tone_map(std::string_view name);

}  // namespace jade::dev
