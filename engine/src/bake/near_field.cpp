#include "bake/near_field.hpp"

#include <jade/error.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>

namespace jade::bake {

namespace {

// Calls visit(i, j, is_disk_candidate) for every near-list entry of the vertices in [begin, end).
template <class Visit>
void walk_near_pairs(const PreparedMesh& mesh, const Bvh& tree, float margin, float min_reach, size_t begin, size_t end,
                     size_t stride, Visit&& visit)
{
    auto disk_reach = [&](uint32_t j) {
        return margin * kNearFactor * std::sqrt(mesh.areas[j] / std::numbers::pi_v<float>);
    };
    auto reach = [&](uint32_t j) { return std::max(disk_reach(j), margin * min_reach); };
    std::vector<float> node_reach(tree.nodes.size(), 0.0f);
    for (size_t k = 0; k < tree.nodes.size(); ++k) {
        uint32_t first = tree.nodes[k].first();
        for (uint32_t s = first; s < first + tree.counts[k]; ++s)
            node_reach[k] = std::max(node_reach[k], reach(tree.order[s]));
    }
    for (size_t i = begin; i < end; i += stride) {
        const glm::vec3 x = mesh.positions[i];
        uint32_t k = 0;
        while (k < tree.nodes.size()) {
            const BvhNode& node = tree.nodes[k];
            if (glm::distance(x, glm::clamp(x, node.lo, node.hi)) >= node_reach[k]) {
                k = node.escape;
                continue;
            }
            if (!node.leaf()) {
                ++k;
                continue;
            }
            for (uint32_t s = node.first(); s < node.first() + tree.counts[k]; ++s) {
                const uint32_t j = tree.order[s];
                if (j == i) continue;
                const float r = glm::distance(x, mesh.positions[j]);
                if (r < reach(j)) visit(i, j, r < disk_reach(j));
            }
            k = node.escape;
        }
    }
}

}  // namespace

uint64_t sample_near_entries(const PreparedMesh& mesh, const Bvh& tree, float margin, float min_reach)
{
    const size_t n = mesh.vertex_count(), stride = std::max<size_t>(1, n / 1024);
    uint64_t entries = 0, sampled = 0;
    walk_near_pairs(mesh, tree, margin, min_reach, 0, n, stride, [&](size_t, uint32_t, bool) { ++entries; });
    for (size_t i = 0; i < n; i += stride) ++sampled;
    return uint64_t(double(entries) * double(n) / double(std::max<uint64_t>(sampled, 1)));
}

NearLists build_near_lists(const PreparedMesh& mesh, const Bvh& tree, float margin, float min_reach)
{
    const size_t n = mesh.vertex_count();
    // Per-target rows, found in parallel, then concatenated.
    std::vector<std::vector<uint32_t>> rows(n), points(n);
    auto work = [&](size_t begin, size_t end) {
        walk_near_pairs(mesh, tree, margin, min_reach, begin, end, 1,
                        [&](size_t i, uint32_t j, bool disk) { (disk ? rows : points)[i].push_back(j); });
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

std::vector<NearWindow> plan_near_windows(std::span<const uint32_t> offsets, uint64_t align, uint64_t max_bytes)
{
    max_bytes = (max_bytes / align) * align - align;  // room for the aligned start
    const uint32_t rows = uint32_t(offsets.size() - 1);
    std::vector<NearWindow> windows;
    for (uint32_t k0 = 0; k0 < rows;) {
        const uint64_t start = (uint64_t(offsets[k0]) * 4 / align) * align;
        if (uint64_t(offsets[k0 + 1]) * 4 - start > max_bytes)
            throw Error("t_m: the near-field list of vertex slot " + std::to_string(k0) + " (" +
                        std::to_string(offsets[k0 + 1] - offsets[k0]) +
                        " entries) exceeds the device's texel-buffer range");
        // The longest run from k0 that fits (binary search over the monotone offsets).
        uint32_t lo = k0 + 1, hi = rows;
        while (lo < hi) {
            const uint32_t mid = lo + (hi - lo + 1) / 2;
            if (uint64_t(offsets[mid]) * 4 - start <= max_bytes)
                lo = mid;
            else
                hi = mid - 1;
        }
        windows.push_back({k0, lo - k0, uint32_t(start / 4), std::max<uint64_t>(uint64_t(offsets[lo]) * 4 - start, 4)});
        k0 = lo;
    }
    return windows;
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
        out.indices.insert(out.indices.end(), lists.indices.begin() + lists.offsets[v],
                           lists.indices.begin() + lists.offsets[v + 1]);
        out.offsets[k + 1] = uint32_t(out.indices.size());
    }
    return out;
}

}  // namespace jade::bake
