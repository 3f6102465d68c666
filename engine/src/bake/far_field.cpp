// bake/far_field.cpp - choose_far_field: TmMethod::Auto's rule (bake/far_field.hpp).
#include "bake/far_field.hpp"

#include "bake/bake_common.hpp"

#include <jade/dev/material.hpp>

namespace jade::bake {

Bvh build_point_tree(const PreparedMesh& mesh) { return build_bvh(mesh.positions, mesh.positions, kPointLeafSize); }

FarField choose_far_field(const PreparedMesh& mesh, const Material& material, const BakeSettings& s,
                          const Bvh& point_tree, float near_margin)
{
    FarField f;
    const size_t n = mesh.vertex_count();
    if (uses_exact_tm(s.method, n)) return f;
    f.method = TmMethod::Clustered;
    if (s.method != TmMethod::Grid && s.method != TmMethod::Auto) return f;
    f.grid = plan_grid(mesh, material, dev::is_grey(material) ? 1 : 3, s.tm_grid_resolution,
                       near_margin > kStaticNearMargin, near_margin);
    f.near_entries = f.grid->feasible ? sample_near_entries(mesh, point_tree, near_margin, float(f.grid->r_cut)) : 0;
    f.long_lists = f.near_entries * 4 > kGridMaxNearBytes;
    if (s.method == TmMethod::Grid) {
        if (f.grid->feasible && !f.long_lists) f.method = TmMethod::Grid;
        return f;
    }
    if (f.grid->coarsened || f.long_lists || f.near_entries > 4 * f.grid->near_entries(n, near_margin))
        f.grid.reset();
    else
        f.method = TmMethod::Grid;
    return f;
}

}  // namespace jade::bake
