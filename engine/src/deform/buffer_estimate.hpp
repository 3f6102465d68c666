// deform/buffer_estimate.hpp - what a MeshDeformer allocates on the GPU, before it exists (for
// plan_scene, jade/scene.hpp). Private to the engine.
#pragma once

#include <jade/dev/scene.hpp>  // BufferEstimate

#include <cstddef>
#include <vector>

namespace jade::deform {

/// The device buffers of a MeshDeformer of a mesh of `vertices` bake vertices and `triangles`
/// triangles (without a skin: set_skin adds its own), named as it names them. Exact.
std::vector<dev::BufferEstimate> estimate_buffers(size_t vertices, size_t triangles);

}  // namespace jade::deform
