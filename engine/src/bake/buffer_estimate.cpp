// bake/buffer_estimate.cpp - estimate_buffers: the buffers of one mesh's bake (Baker::Impl::
// MeshBake: the shared bake::MeshState and each pass's own) before a bake allocates them
// (upload_mesh, the passes' prepare, prepare_tm).
//
// Sizes are written with the same element types and constants the passes allocate with. What
// depends on the geometry rather than on the counts is estimated with three constants measured
// on the test meshes (sphere, box, grid, bunny; tests/test_scene.cpp compares the total with the
// bytes the Context really allocated, dev::created_objects(context).device_buffer_bytes):
//   - the triangle BVH (leaves of ≤ kTriangleLeafSize triangles) has about kRayNodesPerTriangle
//     nodes per triangle, the point tree (leaves of ≤ kPointLeafSize points)
//     kPointNodesPerVertex nodes per vertex;
//   - a near-field list holds about kNearEntriesPerVertex sources per vertex on a regular mesh
//     (sources within 4 disk radii: π·(4·0.56 h)² / (0.87 h²) ≈ 18 neighbours at spacing h),
//     times (margin / kStaticNearMargin)² for a deforming mesh's wider margin.
// Host-visible staging is not counted.
#include "bake/buffer_estimate.hpp"

#include "bake/bake_common.hpp"
#include "bake/far_field.hpp"

#include <cmath>
#include <optional>

namespace jade::bake {
namespace {

constexpr double kRayNodesPerTriangle = 0.6;
constexpr double kPointNodesPerVertex = 0.3;
constexpr double kNearEntriesPerVertex = 20.0;
// Bytes per ray item: three RGBA32UI texels (bake/ray_items.hpp).
constexpr double kRayItemBytes = 3 * sizeof(glm::uvec4);
// Extra near-list entries for a window's aligned start and minimum size (prepare_tm).
constexpr double kNearSlack = 64;

uint64_t bytes(double b) { return std::max<uint64_t>(gpu::kMinBufferBytes, uint64_t(b + 0.5)); }

}  // namespace

std::vector<dev::BufferEstimate> estimate_buffers(const PreparedMesh& mesh, const Material& material,
                                                  const BakeSettings& s, bool dynamic, bool thickness)
{
    const double n = double(mesh.vertex_count()), tris = double(mesh.triangle_count());
    const double vec3 = sizeof(glm::vec3), word = sizeof(uint32_t);
    const double ray_nodes = kRayNodesPerTriangle * tris;
    const double ray_items = ray_nodes + tris;
    const float margin = dynamic ? kDynamicNearMargin : kStaticNearMargin;
    double near_entries = kNearEntriesPerVertex * n * (margin * margin) / (kStaticNearMargin * kStaticNearMargin);
    // The far field by the rule the bake's set-up applies (bake/far_field.hpp), on the same tree.
    const FarField far = choose_far_field(mesh, material, s, build_point_tree(mesh), margin);
    const bool exact = far.method == TmMethod::Exact;
    const GridPlan* grid = far.method == TmMethod::Grid ? &*far.grid : nullptr;
    if (grid) near_entries = double(grid->near_entries(mesh.vertex_count(), margin));
    std::vector<dev::BufferEstimate> b = {
        {"positions", bytes(vec3 * n)},
        {"normals", bytes(vec3 * n)},
        {"areas", bytes(sizeof(float) * n)},
        {"ray items (BVH nodes and triangles)", bytes(kRayItemBytes * ray_items)},
        {"ao hit counts", bytes(word * n)},
        {"ao", bytes(sizeof(float) * n)},
        {"profiles", bytes(3.0 * sizeof(GpuProfile))},
        {kTmValues.name, bytes(kTmValues.bytes_per_vertex * n)},
        {kTmPartialSums.name, bytes(kTmPartialSums.bytes_per_vertex * n)},
        {kTmPartialCompensation.name, bytes(kTmPartialCompensation.bytes_per_vertex * n)},
        {kTmNormalSums.name, bytes(kTmNormalSums.bytes_per_vertex * n)},
        {"near-field offsets", bytes(word * (n + 1))},
        {"near-field disk candidates", bytes(word * n)},
        {"near-field sources", bytes(word * (near_entries + kNearSlack))},
        {"point order", bytes(word * n)},
    };
    if (thickness && s.thickness.enabled()) {
        b.push_back({"thickness sums (per ray slice)", bytes(word * n)});
        b.push_back({"thickness", bytes(sizeof(float) * n)});
    }
    if (exact) {
        b.push_back({kTmSources.name, bytes(kTmSources.bytes_per_vertex * n)});
    } else if (grid) {
        b.push_back({kTmSources.name, bytes(kTmSources.bytes_per_vertex * n)});
        b.push_back({"t_m grid", bytes(double(grid->bytes()))});
    } else {
        const double nodes = kPointNodesPerVertex * n;
        // Nodes (4 texels each) then the sources from a texel that is a multiple of 16.
        const double first_point = std::ceil(4.0 * nodes / 16.0) * 16.0;
        b.push_back({"point tree nodes", bytes(sizeof(BvhNode) * nodes)});
        b.push_back({"point tree levels", bytes(word * nodes)});
        b.push_back({"t_m cluster tree and sources",
                     bytes(sizeof(glm::uvec4) * first_point + double(kTmSources.bytes_per_vertex) * n)});
        b.push_back({kTmResume.name, bytes(kTmResume.bytes_per_vertex * n)});
    }
    if (dynamic) {  // refit data (RayRefitPass::prepare)
        b.push_back({"triangle indices", bytes(3 * word * tris)});
        b.push_back({"ray item origins", bytes(word * ray_items)});
        b.push_back({"ray refit work", bytes(sizeof(glm::uvec2) * ray_items)});
    }
    return b;
}

}  // namespace jade::bake
