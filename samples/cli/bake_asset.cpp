// bake_asset.cpp - `jade bake ASSET.gltf|.glb`: every mesh of the asset baked on the GPU (the
// instance rule of jade::GltfAsset) and the asset written back whole with the attributes.
#include "bake_record.hpp"

#include <jade/dev/context.hpp>
#include <jade/dev/clock.hpp>
#include <jade/dev/io.hpp>
#include <jade/io.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <chrono>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

namespace jade::cli {

namespace {

/// The diagonal of the bounding box of every target: the caller's material is sized by the
/// whole asset (its default: the asset is 100 mm across), so that its parts share one scale.
double asset_diagonal(const GltfAsset& asset)
{
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const auto& t : asset.targets())
        for (const auto& p : t.mesh.positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    return asset.targets().empty() ? 0.0 : glm::length(hi - lo);
}

std::string primitive_list(const std::vector<int>& primitives)
{
    std::ostringstream out;
    for (size_t i = 0; i < primitives.size(); ++i) out << (i ? "," : "") << primitives[i];
    return out.str();
}

}  // namespace

void bake_asset(const Args& args, const std::filesystem::path& in, const std::filesystem::path& out,
                const BakeSettings& settings)
{
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    std::vector<std::string> warnings;
    const GltfAsset asset = GltfAsset::load(in, &warnings, read_options(args));
    for (const auto& w : warnings) std::fprintf(stderr, "jade: warning: %s\n", w.c_str());
    // The output replaces one file: never one the asset is read from (its buffer or an image),
    // or the asset would no longer load. Compared as files (links, `..`, hard links), not names.
    for (size_t i = 1; i < dev::asset_files(asset).size(); ++i) {
        std::error_code ec;
        if (std::filesystem::exists(out, ec) && std::filesystem::equivalent(out, dev::asset_files(asset)[i], ec))
            throw Error("--out " + out.string() + ": is " + dev::asset_files(asset)[i].string() + ", a file that " +
                        dev::asset_name(asset) + " reads (its buffer or image); writing there would break the input");
    }
    if (asset.targets().empty()) throw Error(dev::asset_name(asset) + ": no mesh has triangles to bake");
    const Material fallback = material_from_args(args, asset_diagonal(asset));

    auto ctx = make_context(args);
    if (args.flag("verbose")) std::fprintf(stderr, "jade: device %s\n", dev::device_info(*ctx).name.c_str());
    Baker baker(*ctx);
    std::vector<BakedAttributes> baked;
    std::map<std::string, size_t> material_index;  // record: each distinct material once
    std::string materials, bakes, settings_json;
    size_t vertices = 0;
    for (const auto& target : asset.targets()) {
        const Material& material = target.material ? *target.material : fallback;
        PreparedMesh prepared;
        const BakeResult r = bake_at_unit_scale(baker, target.mesh, material, settings, prepared);
        std::fprintf(stderr, "jade: %s primitives %s: %zu vertices (%zu after welding), material %s [%s], in %s: %s\n",
                     target.mesh.name.c_str(), primitive_list(target.primitives).c_str(), target.mesh.positions.size(),
                     prepared.vertex_count(), material.name.c_str(), target.material_name.c_str(), target.space.c_str(),
                     format_ms(r.timings.wall_ms).c_str());
        BakedAttributes b;
        b.ao = dev::to_render_vertices(prepared, r.ao, 0.0f);
        b.tm = dev::to_render_vertices(prepared, r.tm, glm::vec3(0.0f));
        if (!r.thickness.empty()) b.thickness = dev::to_render_vertices(prepared, r.thickness, 0.0f);
        if (!r.scattering_normal.empty()) {
            b.scattering_normal = dev::to_render_vertices(prepared, r.scattering_normal, glm::vec3(0.0f, 0.0f, 1.0f));
            b.normal_spread = dev::to_render_vertices(prepared, r.normal_spread, glm::vec3(0.0f));
        }
        b.material = material;
        baked.push_back(std::move(b));
        vertices += target.mesh.positions.size();

        const std::string m = record::material(material);
        auto [it, added] = material_index.emplace(m, material_index.size());
        if (added) materials += std::string(materials.empty() ? "" : ",") + m;
        if (settings_json.empty()) settings_json = record::settings(settings, r);
        std::ostringstream os;
        os << "{\"mesh\":" << target.mesh_index << ",\"primitives\":[" << primitive_list(target.primitives)
           << "],\"material\":" << it->second << ",\"gltf_material\":" << record::quoted(target.material_name)
           << ",\"space\":" << record::quoted(target.space) << ",\"vertices\":" << target.mesh.positions.size()
           << ",\"bake_vertices\":" << prepared.vertex_count()
           << ",\"thickness\":" << (r.thickness.empty() ? "false" : "true") << ",\"timings_ms\":" << record::timings(r)
           << "}";
        bakes += std::string(bakes.empty() ? "" : ",") + os.str();
    }
    const double wall = ms_since(t0);
    std::ostringstream extras;
    extras
        << "{\"jade\":{\"version\":2," << record::units()
        << ",\"instance_rule\":\"each mesh baked once, all its triangle primitives together, in the world space of its "
           "first instance in the default scene (node scale included); a skinned mesh in its bind pose; every instance "
           "shares the values\",\"settings\":"
        << settings_json << ",\"materials\":[" << materials << "],\"bakes\":[" << bakes << "],\"wall_ms\":" << wall
        << "}}";
    save_baked_asset(out, asset, baked, extras.str());
    std::fprintf(stderr, "jade: %zu bakes, %zu vertices, %s in all\n", baked.size(), vertices, format_ms(wall).c_str());
}

}  // namespace jade::cli
