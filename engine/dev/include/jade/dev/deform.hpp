// jade/dev/deform.hpp - the check of a procedural deformer's parameters, for the CLI's flags
// before any GPU work (MeshDeformer::deform and record make the same check). Declared for
// jade::dev, defined in jade::jade.
#pragma once

#include <jade/deform.hpp>

namespace jade::dev {

/// Throws jade::Error naming the parameter of `deformer` that is out of range or not finite.
void validate_deformer(const ProceduralDeformer& deformer);

}  // namespace jade::dev
