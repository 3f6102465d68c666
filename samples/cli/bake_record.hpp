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

/// Bakes every mesh of the glTF asset `in` (the instance rule of jade::GltfAsset) and writes it
/// back whole to `out` with _AO, _TM, _THICKNESS and the record in asset.extras.jade.
void bake_asset(const Args& args, const std::filesystem::path& in, const std::filesystem::path& out,
                const BakeSettings& settings);

}  // namespace jade::cli
