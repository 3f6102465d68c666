// bake/buffer_estimate.hpp - what a bake will allocate on the GPU, before it runs (for
// plan_scene, jade/scene.hpp). Private to the engine.
#pragma once

#include <jade/bake.hpp>
#include <jade/dev/scene.hpp>  // BufferEstimate

#include <vector>

namespace jade::bake {

/// The device buffers of one mesh's bake (Baker::Impl::MeshBake, bake/baker_impl.hpp: the
/// shared bake::MeshState and each pass's own), named as the bake names them: a static bake
/// (Baker::bake) or, with `dynamic`, the state a DynamicBake keeps; the thickness buffers only
/// with `thickness` (a material with a transmission term) and settings.thickness enabled. What
/// depends on the geometry (tree sizes, near-list lengths) is estimated: buffer_estimate.cpp
/// says how.
std::vector<dev::BufferEstimate> estimate_buffers(const PreparedMesh& mesh, const Material& material,
                                                  const BakeSettings& settings, bool dynamic, bool thickness);

}  // namespace jade::bake
