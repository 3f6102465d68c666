// jade info [MESH]: the device, or a mesh after preparation.
#include "commands.hpp"

#include <jade/dev/context.hpp>
#include <jade/dev/io.hpp>
#include <jade/io.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

namespace jade::cli {

static void print_device(const dev::DeviceInfo& d)
{
    std::printf("device            %s (%s)\n", d.name.c_str(), d.type.c_str());
    std::printf("driver            %s\n", d.driver.c_str());
    std::printf("Vulkan            %s\n", d.api_version_string().c_str());
    std::printf("storage buffer    %llu MiB max range\n", (unsigned long long)(d.max_storage_buffer_range >> 20));
    std::printf("work groups       %u x %u x %u max count, %u invocations\n", d.max_workgroup_count[0],
                d.max_workgroup_count[1], d.max_workgroup_count[2], d.max_workgroup_invocations);
    std::printf("subgroup size     %u\n", d.subgroup_size);
    std::printf("float64           %s\n", d.float64 ? "yes" : "no");
    std::printf("int64 atomics     %s\n", d.int64_atomics ? "yes" : "no");
    std::printf("timestamp period  %.3g ns\n", d.timestamp_period_ns);
    std::printf("device memory     %.1f GiB\n", double(d.device_local_heap_bytes) / (1u << 30));
}

/// What `jade bake` recorded in a glTF's asset.extras.jade (bake_record.hpp), if anything.
static void print_bake_record(const std::string& path, const ReadOptions& options)
{
    std::string ext = std::filesystem::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".glb" && ext != ".gltf") return;
    const std::string text = dev::asset_extras_json(GltfAsset::load(path, nullptr, options));
    const auto extras = nlohmann::json::parse(text.empty() ? "{}" : text, nullptr, false);
    if (!extras.is_object() || !extras.contains("jade") || !extras["jade"].is_object()) {
        std::printf("baked by jade     no (no asset.extras.jade)\n");
        return;
    }
    const auto& j = extras["jade"];
    auto str = [](const nlohmann::json& v) {
        if (v.is_string()) return v.get<std::string>();
        if (!v.is_number_float()) return v.dump();
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
        return std::string(buf);
    };
    const auto& s = j.value("settings", nlohmann::json::object());
    std::printf("baked by jade     record version %s; AO %s rays (seed %s, max distance %s of the diagonal), t_m %s "
                "(theta %s), thickness %s rays\n",
                str(j.value("version", nlohmann::json())).c_str(), str(s.value("ao_rays", nlohmann::json())).c_str(),
                str(s.value("ao_seed", nlohmann::json())).c_str(),
                str(s.value("ao_max_distance_rel", nlohmann::json())).c_str(),
                str(s.value("tm_method", nlohmann::json())).c_str(),
                str(s.value("tm_epsilon", nlohmann::json())).c_str(),
                str(s.value("thickness_rays", nlohmann::json(0))).c_str());
    if (j.contains("instance_rule")) std::printf("instance rule     %s\n", str(j["instance_rule"]).c_str());
    std::vector<nlohmann::json> materials;
    if (j.contains("material")) materials.push_back(j["material"]);
    for (const auto& m : j.value("materials", nlohmann::json::array())) materials.push_back(m);
    for (size_t i = 0; i < materials.size(); ++i) {
        const auto& m = materials[i];
        std::string profiles;
        for (const auto& p : m.value("profiles", nlohmann::json::array()))
            profiles += std::string(profiles.empty() ? "" : ", ") + p.dump();
        std::printf("material %-8zu %s: strength %s, %s\n", i, str(m.value("name", nlohmann::json())).c_str(),
                    str(m.value("strength", nlohmann::json())).c_str(), profiles.c_str());
    }
    for (const auto& b : j.value("bakes", nlohmann::json::array())) {
        std::string prims;
        for (const auto& p : b.value("primitives", nlohmann::json::array()))
            prims += std::string(prims.empty() ? "" : ",") + p.dump();
        std::printf(
            "bake              mesh %s primitives %s: %s vertices, material %s (%s), %s%s, %s ms\n",
            str(b.value("mesh", nlohmann::json())).c_str(), prims.c_str(),
            str(b.value("vertices", nlohmann::json())).c_str(), str(b.value("material", nlohmann::json())).c_str(),
            str(b.value("gltf_material", nlohmann::json())).c_str(), str(b.value("space", nlohmann::json())).c_str(),
            b.value("thickness", false) ? ", with thickness" : "",
            str(b.value("timings_ms", nlohmann::json::object()).value("wall", nlohmann::json())).c_str());
    }
}

static void print_mesh(const std::string& path, const ReadOptions& options)
{
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    ReadOptions read = options;
    std::optional<Material> material;  // a baked file's JADE_materials_translucency
    read.baked_material = &material;
    TriangleMesh mesh = load_mesh_arg(path, read);
    auto t1 = Clock::now();
    PreparedMesh p = prepare_mesh(mesh);
    auto t2 = Clock::now();
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("mesh              %s\n", mesh.name.c_str());
    std::printf("input             %zu vertices, %zu triangles\n", p.input_vertices, p.input_triangles);
    std::printf("prepared          %zu vertices, %zu triangles\n", p.vertex_count(), p.triangle_count());
    std::printf("welded            %zu vertices\n", p.welded_vertices);
    std::printf("dropped           %zu degenerate triangles, %zu unused vertices\n", p.dropped_triangles,
                p.unused_vertices);
    std::printf("bounding box      (%g, %g, %g) .. (%g, %g, %g) mesh units\n", p.bbox_min.x, p.bbox_min.y, p.bbox_min.z,
                p.bbox_max.x, p.bbox_max.y, p.bbox_max.z);
    std::printf("diagonal          %g mesh units\n", p.diagonal);
    std::printf("surface area      %g units^2\n", dev::total_area(p));
    // The range of the finite values, and how many are not finite (NaN or Inf), so that an
    // attribute full of NaN shows as such and a partial one is not hidden.
    auto range = [](const char* label, const float* v, size_t n, size_t stride, const char* unit) {
        for (size_t c = 0; c < stride; ++c) {
            float lo = INFINITY, hi = -INFINITY;
            size_t bad = 0;
            for (size_t i = c; i < n * stride; i += stride) {
                if (!std::isfinite(v[i])) {
                    ++bad;
                    continue;
                }
                lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
            }
            std::printf(c == 0 ? "%-18s" : "  ", c == 0 ? label : "");
            if (stride == 3) std::printf("%c ", "RGB"[c]);
            if (bad < n)
                std::printf("%.4g .. %.4g", lo, hi);
            else
                std::printf("none finite");
            if (bad) std::printf(" (%zu of %zu not finite)", bad, n);
        }
        std::printf("%s\n", unit);
    };
    if (!mesh.baked_ao.empty()) range("baked AO", mesh.baked_ao.data(), mesh.baked_ao.size(), 1, "");
    if (!mesh.baked_tm.empty()) range("baked t_m", &mesh.baked_tm[0].x, mesh.baked_tm.size(), 3, "");
    if (!mesh.baked_thickness.empty())
        range("baked thickness", mesh.baked_thickness.data(), mesh.baked_thickness.size(), 1, " mesh units");
    if (!mesh.baked_normal_spread.empty())
        range("normal spread", &mesh.baked_normal_spread[0].x, mesh.baked_normal_spread.size(), 3, "");
    if (!mesh.baked_scattering_normal.empty())
        std::printf("scattering normal %zu vertices\n", mesh.baked_scattering_normal.size());
    if (material)
        std::printf("baked material    %s (JADE_materials_translucency): albedo %.4g %.4g %.4g, strength %g + %g x "
                    "spread, transmission %s\n",
                    material->name.c_str(), material->albedo.x, material->albedo.y, material->albedo.z,
                    material->strength, material->spread_strength, material->transmission.enabled() ? "on" : "off");
    print_bake_record(path, options);
    std::printf("timings           load %s, prepare %s\n", format_ms(ms(t0, t1)).c_str(),
                format_ms(ms(t1, t2)).c_str());
}

int cmd_info(int argc, char** argv)
{
    const char* const usage =
        "usage: jade info [MESH]\n\nWithout MESH: the Vulkan device Jade would use. With MESH: counts "
        "after\npreparation (welding, degenerate triangles), bounds and timings; for a file written by jade "
        "bake,\nthe ranges of the baked attributes and what was baked with which settings.";
    Args args("info",
              all_options({device_options(), input_options(), {{"materials", "", "list the material presets"}}}), argc,
              argv, 2);
    if (print_help(args, usage)) return 0;
    if (args.positional().size() > 1) args.fail("takes at most one mesh");
    if (args.flag("materials")) {
        for (const auto& n : material_preset_names()) std::printf("%s\n", n.c_str());
        return 0;
    }
    if (!args.positional().empty()) {
        print_mesh(args.positional()[0], read_options(args));
        return 0;
    }
    auto ctx = make_context(args);
    print_device(dev::device_info(*ctx));
    auto all = dev::list_devices();
    if (all.size() > 1) {
        std::printf("all devices      ");
        for (auto& n : all) std::printf(" [%s]", n.c_str());
        std::printf("\n");
    }
    return 0;
}

}  // namespace jade::cli
