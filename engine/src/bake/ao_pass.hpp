// bake/ao_pass.hpp - the AO pass (jade/bake.hpp AoSettings): the triangle BVH flattened into
// ray items (MeshState: the thickness pass traces them too), cosine rays per vertex in slices
// (ao_trace.comp) and A_o from the hit counts (ao_resolve.comp); amortised, the vertices whose
// fresh slice changed have their other slices traced again (ao_changed.comp, ao_retrace.comp).
// Recorded by the static bake and by DynamicBake. Private to engine/src/bake.
#pragma once

#include "bake/mesh_state.hpp"
#include "bake/ray_items.hpp"

namespace jade::bake {

// The pass's kernels, made on first use; one per Baker, shared by every mesh it bakes.
class AoPass {
public:
    // One mesh's buffers: hit counts per ray slice, per vertex; amortised with retrace_changed
    // (Amortisation), the fresh slice's counts from the frame that last traced it, and
    // ao_changed.comp's indirect dispatch and list of vertices.
    struct Buffers {
        gpu::Buffer hits, previous, changed_list;
        // Reallocates them for `slices` ray slices (DynamicBake's amortisation changes them).
        void set_slices(gpu::Context& ctx, uint32_t vertex_count, uint32_t slices);
    };
    // The triangle BVH and its ray items, for a refit's work lists (bake/ray_refit_pass.hpp).
    struct Tree {
        Bvh bvh;
        RayItems items;
    };

    explicit AoPass(gpu::Context& ctx) : ctx_(ctx) {}

    // Builds the BVH, uploads its ray items into m, allocates the hit counts and m.ao.
    Tree prepare(Buffers& b, MeshState& m, const PreparedMesh& mesh) const;
    // Traces the ray slices [first, first + count) of m.ao_slices (ao_trace.comp) into their
    // hit counts, then resolves A_o from the counts of every slice. `retrace_changed`, with one
    // slice of several: the vertices whose slice changed have their other slices traced too
    // (ao_changed.comp, Amortisation::retrace_changed).
    void record(VkCommandBuffer cmd, Buffers& b, const MeshState& m, const AoSettings& s, uint32_t first = 0,
                uint32_t count = 0, bool retrace_changed = false);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> trace_, resolve_, changed_, retrace_;
};

}  // namespace jade::bake
