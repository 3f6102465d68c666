// bake/ray_refit_pass.cpp - the ray items' refit (bake/ray_refit_pass.hpp).
#include "bake/ray_refit_pass.hpp"

namespace jade::bake {

void RayRefitPass::prepare(Buffers& b, const AoPass::Tree& tree, const PreparedMesh& mesh) const
{
    const Bvh& bvh = tree.bvh;
    const RayItems& items = tree.items;
    check_storage_range(ctx_, VkDeviceSize(items.count()) * 48, "ray items (refitted as a storage buffer)");
    // Work for ray_refit.comp: every triangle item, then the node items level by level,
    // deepest first, each with its leaf's triangle count (0: inner node).
    std::vector<uint32_t> item_of_node(bvh.nodes.size());
    std::vector<glm::uvec2> work;
    for (uint32_t k = 0; k < items.count(); ++k) {
        if (items.origin[k] & kItemTriangleBit)
            work.push_back({k, 0});
        else
            item_of_node[items.origin[k]] = k;
    }
    b.work_offsets = {0, uint32_t(work.size())};
    BvhLevels levels = bvh_levels(bvh);
    for (size_t l = 0; l < levels.count(); ++l) {
        for (uint32_t k = levels.offsets[l]; k < levels.offsets[l + 1]; ++k) {
            const BvhNode& node = bvh.nodes[levels.nodes[k]];
            work.push_back({item_of_node[levels.nodes[k]], node.leaf() ? node.leaf_count() : 0});
        }
        b.work_offsets.push_back(uint32_t(work.size()));
    }
    b.indices = gpu::Buffer::from(ctx_, mesh.indices, kStorageUsage, "triangle indices");
    b.item_origin = gpu::Buffer::from(ctx_, items.origin, kStorageUsage, "ray item origins");
    b.work = gpu::Buffer::from(ctx_, work, kStorageUsage, "ray refit work");
}

// Ray items follow the current positions: triangles, then node boxes bottom-up.
void RayRefitPass::record(VkCommandBuffer cmd, const Buffers& b, const MeshState& m)
{
    const auto& k =
        lazy_kernel(ctx_, kernel_,
                    {"ray_refit", shaders::ray_refit_comp(), gpu::storage_bindings(5), sizeof(RayRefitPush), 64, {}});
    for (size_t r = 0; r + 1 < b.work_offsets.size(); ++r) {
        const uint32_t first = b.work_offsets[r], count = b.work_offsets[r + 1] - first;
        k.dispatch(cmd, count, RayRefitPush{count, first, r == 0 ? 0u : 1u},
                   {m.positions, b.indices, b.item_origin, b.work, m.ray_items});
        gpu::compute_barrier(cmd);
    }
}

}  // namespace jade::bake
