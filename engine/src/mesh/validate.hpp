// mesh/validate.hpp - the checks every TriangleMesh must pass, for prepare_mesh and the readers
// and writers of jade::io. Private to the engine.
#pragma once

#include <jade/mesh.hpp>

namespace jade {

/// Checks what every TriangleMesh must satisfy: an index count that is a multiple of 3, indices
/// in range, finite positions, normals absent or one per position. Throws jade::Error naming
/// mesh.name and the first offending element, e.g.
/// "bunny.off: triangle 12 (vertex index 40912) out of range for 37706 vertices".
void validate_mesh(const TriangleMesh& mesh);

}  // namespace jade
