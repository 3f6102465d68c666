#include "bake/near_field.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

namespace jade::bake {

NearLists build_near_lists(const PreparedMesh& mesh, const Bvh& tree, float margin, float min_reach)
{
    const size_t n = mesh.vertex_count();
    auto disk_reach = [&](uint32_t j) { return margin * kNearFactor * std::sqrt(mesh.areas[j] / std::numbers::pi_v<float>); };
    auto reach = [&](uint32_t j) { return std::max(disk_reach(j), margin * min_reach); };

    // Largest reach inside each node: its range of tree-ordered vertices.
    std::vector<float> node_reach(tree.nodes.size(), 0.0f);
    for (size_t k = 0; k < tree.nodes.size(); ++k) {
        uint32_t first = tree.nodes[k].first();
        for (uint32_t s = first; s < first + tree.counts[k]; ++s) node_reach[k] = std::max(node_reach[k], reach(tree.order[s]));
    }

    // Per-target rows, found in parallel, then concatenated.
    std::vector<std::vector<uint32_t>> rows(n), points(n);
    auto work = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const glm::vec3 x = mesh.positions[i];
            uint32_t k = 0;
            while (k < tree.nodes.size()) {
                const BvhNode& node = tree.nodes[k];
                glm::vec3 nearest = glm::clamp(x, node.lo, node.hi);
                if (glm::distance(x, nearest) >= node_reach[k]) {
                    k = node.escape;
                    continue;
                }
                if (!node.leaf()) {
                    ++k;
                    continue;
                }
                uint32_t first = node.first();
                for (uint32_t s = first; s < first + tree.counts[k]; ++s) {
                    uint32_t j = tree.order[s];
                    if (j == i) continue;
                    const float r = glm::distance(x, mesh.positions[j]);
                    if (r < disk_reach(j)) rows[i].push_back(j);
                    else if (r < reach(j)) points[i].push_back(j);
                }
                k = node.escape;
            }
        }
    };
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work, n * t / threads, n * (t + 1) / threads);
    for (auto& t : pool) t.join();

    NearLists lists;
    lists.offsets.resize(n + 1, 0);
    lists.disk_counts.resize(n);
    for (size_t i = 0; i < n; ++i) {
        lists.disk_counts[i] = uint32_t(rows[i].size());
        lists.offsets[i + 1] = lists.offsets[i] + uint32_t(rows[i].size() + points[i].size());
    }
    lists.indices.reserve(lists.offsets[n]);
    for (size_t i = 0; i < n; ++i) {
        lists.indices.insert(lists.indices.end(), rows[i].begin(), rows[i].end());
        lists.indices.insert(lists.indices.end(), points[i].begin(), points[i].end());
    }
    return lists;
}

NearLists reorder_rows(const NearLists& lists, std::span<const uint32_t> order)
{
    NearLists out;
    out.offsets.resize(order.size() + 1, 0);
    out.disk_counts.resize(order.size());
    out.indices.reserve(lists.indices.size());
    for (size_t k = 0; k < order.size(); ++k) {
        const uint32_t v = order[k];
        out.disk_counts[k] = lists.disk_counts[v];
        out.indices.insert(out.indices.end(), lists.indices.begin() + lists.offsets[v], lists.indices.begin() + lists.offsets[v + 1]);
        out.offsets[k + 1] = uint32_t(out.indices.size());
    }
    return out;
}

}  // namespace jade::bake
