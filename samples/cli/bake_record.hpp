// bake_record.hpp - what `jade bake` records in the asset's extras ("jade": {...}), and the bake
// of a whole glTF asset (bake_asset.cpp). `jade info` reads the record back (cmd_info.cpp).
#pragma once

#include "commands.hpp"

#include <filesystem>
#include <string>

namespace jade::cli {

namespace record {
/// JSON fragments (valid JSON text: every number finite, strings escaped).
std::string units();  ///< "\"units\":\"...\"" - a member, not an object
std::string material(const Material& m);
std::string settings(const BakeSettings& s, const BakeResult& r);
std::string timings(const BakeResult& r);
std::string quoted(const std::string& text);
}  // namespace record

/// The diagonal of the mesh's bounding box, in double (mesh units).
double diagonal(const TriangleMesh& mesh);

/// Bakes `mesh` scaled by the power of two that brings its diagonal nearest to 1: the bake is
/// scale-invariant (AO distances are fractions of the diagonal, the profile scales with the
/// mesh), and at unit scale areas (units²) and profile values stay well inside float range, so a
/// mesh of 1e20 or 1e-20 units bakes as a unit one would instead of overflowing or underflowing.
/// Powers of two scale exactly: a mesh of diagonal 0.7 .. 1.4 bakes unchanged. The thickness is
/// scaled back to mesh units; `prepared` receives the preparation of the scaled mesh (its
/// render_to_bake map is the mesh's).
BakeResult bake_at_unit_scale(Baker& baker, const TriangleMesh& mesh, const Material& material,
                              const BakeSettings& settings, PreparedMesh& prepared);

/// Bakes every mesh of the glTF asset `in` (the instance rule of jade::GltfAsset) and writes it
/// back whole to `out` with _AO, _TM, _THICKNESS and the record in asset.extras.jade.
void bake_asset(const Args& args, const std::filesystem::path& in, const std::filesystem::path& out,
                const BakeSettings& settings);

}  // namespace jade::cli
