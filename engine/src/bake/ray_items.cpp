#include "bake/ray_items.hpp"

#include <bit>

namespace jade::bake {

namespace {

glm::uvec4 texel(glm::vec3 v, uint32_t w)
{
    return {std::bit_cast<uint32_t>(v.x), std::bit_cast<uint32_t>(v.y), std::bit_cast<uint32_t>(v.z), w};
}

}  // namespace

RayItems flatten_ray_items(const Bvh& bvh, const PreparedMesh& mesh)
{
    const uint32_t nodes = uint32_t(bvh.nodes.size());
    // Item index of every node: the nodes before it plus the triangles of the leaves before it.
    std::vector<uint32_t> item_of(nodes + 1);
    uint32_t items = 0;
    for (uint32_t k = 0; k < nodes; ++k) {
        item_of[k] = items;
        items += 1 + (bvh.nodes[k].leaf() ? bvh.nodes[k].leaf_count() : 0);
    }
    item_of[nodes] = items;

    RayItems out;
    out.texels.reserve(3 * size_t(items));
    out.origin.reserve(items);
    for (uint32_t k = 0; k < nodes; ++k) {
        const BvhNode& n = bvh.nodes[k];
        out.texels.push_back(texel(n.lo, item_of[n.escape]));
        out.texels.push_back(texel(n.hi, 0));
        out.texels.push_back(glm::uvec4(0));
        out.origin.push_back(k);
        if (!n.leaf()) continue;
        for (uint32_t p = n.first(); p < n.first() + n.leaf_count(); ++p) {
            const uint32_t t = bvh.order[p];
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
            out.texels.push_back(texel(a, 0));
            out.texels.push_back(texel(mesh.positions[mesh.indices[3 * t + 1]] - a, 1));
            out.texels.push_back(texel(mesh.positions[mesh.indices[3 * t + 2]] - a, 0));
            out.origin.push_back(t | kItemTriangleBit);
        }
    }
    return out;
}

}  // namespace jade::bake
