// bake/baker_impl.hpp - Baker::Impl, which the static bake (baker.cpp) and the per-frame
// re-bake (dynamic_bake.cpp) share: one owner per pass (bake/*_pass.hpp: its kernels, made on
// first use, and the type of one mesh's buffers for it), and the order in which a mesh's bake
// calls them (its data flow: baker.cpp). Private to engine/src/bake.
#pragma once

#include "bake/bake_common.hpp"
#include "bake/ao_pass.hpp"
#include "bake/clustered_pass.hpp"
#include "bake/exact_pass.hpp"
#include "bake/gather_pass.hpp"
#include "bake/grid_pass.hpp"
#include "bake/mesh_state.hpp"
#include "bake/near_pass.hpp"
#include "bake/ray_refit_pass.hpp"
#include "bake/thickness_pass.hpp"

namespace jade {

// The bake's own vocabulary, for the files that include this one (baker.cpp, dynamic_bake.cpp,
// tm_passes.cpp).
using bake::finish_timings;
using bake::kDynamicNearMargin;
using bake::kGridMaxNearBytes;
using bake::kStaticNearMargin;
using bake::kStorageUsage;
using bake::kTexelUsage;
using bake::read_scattering_normals;
using bake::tm_variant;
using bake::validate_ao_settings;
using bake::validate_tm_settings;

struct Baker::Impl {
    gpu::Context& ctx;
    bake::AoPass ao;
    bake::RayRefitPass ray_refit;
    bake::ThicknessPass thickness;
    bake::GatherPass gather;
    bake::NearPass near;
    bake::ExactPass exact;
    bake::ClusteredPass clustered;
    bake::GridPass grid;

    explicit Impl(gpu::Context& c)
        : ctx(c), ao(c), ray_refit(c), thickness(c), gather(c), near(c), exact(c), clustered(c), grid(c)
    {
    }

    // One mesh's bake: the state the passes share, and each pass's own buffers.
    struct MeshBake : bake::MeshState {
        bake::AoPass::Buffers ao_pass;
        bake::RayRefitPass::Buffers ray_refit;  // a deforming mesh's
        bake::ThicknessPass::Buffers thickness;
        bake::NearPass::Buffers near_lists;
        bake::ClusteredPass::Buffers cluster_tree;
        bake::GridPass::Buffers grids;
        uint64_t tm_bytes() const
        {
            return shared_tm_bytes() + near_lists.bytes() + cluster_tree.bytes() + grids.bytes();
        }
    };
    void upload_mesh(MeshBake& m, const PreparedMesh& mesh, VkBufferUsageFlags extra_usage = 0)
    {
        bake::upload_mesh(ctx, m, mesh, extra_usage);
    }

    // The t_m passes (bake/tm_passes.cpp). Sets up gather → near field → (all pairs | refit →
    // clustered | grid), reading m.ao, writing m.tm. `near_margin` (bake/near_field.hpp) covers
    // how much closer vertices may come.
    void prepare_tm(MeshBake& m, const PreparedMesh& mesh, const Material& material, const BakeSettings& s,
                    float near_margin);

    // What every static bake reads back after its one submission (baker.cpp): t_m with its
    // scattering normals, how t_m was summed, and the timings.
    static void read_tm_result(BakeResult& r, const MeshBake& m, const gpu::GpuTimer& timer, double setup,
                               Clock::time_point t0);

    // Gathers every source and refits the cluster tree, then evaluates t_m for the targets in
    // tree slots [slot_begin, slot_end) (every slot by default; the all-pairs method always
    // evaluates every target).
    void record_tm(VkCommandBuffer cmd, MeshBake& m, const BakeSettings& s, gpu::GpuTimer* timer,
                   uint32_t slot_begin = 0, uint32_t slot_end = ~0u);
};

}  // namespace jade
