// jade bake MESH --out FILE.glb: AO and t_m on the GPU, written on the render vertices.
#include "commands.hpp"

#include <jade/io.hpp>

#include <cstdio>
#include <sstream>

namespace jade::cli {

static std::string profile_json(const ChannelProfile& p)
{
    std::ostringstream os;
    os.precision(9);
    switch (p.kind) {
    case ProfileKind::Burley: os << "{\"kind\":\"burley\",\"d\":" << p.d << "}"; break;
    case ProfileKind::Dipole:
        os << "{\"kind\":\"dipole\",\"sigma_tr\":" << p.sigma_tr << ",\"z_r\":" << p.z_r << ",\"z_v\":" << p.z_v << "}";
        break;
    case ProfileKind::Gaussians:
        os << "{\"kind\":\"gaussians\",\"weights\":[";
        for (uint32_t k = 0; k < p.gaussian_count; ++k) os << (k ? "," : "") << p.weight[k];
        os << "],\"variances\":[";
        for (uint32_t k = 0; k < p.gaussian_count; ++k) os << (k ? "," : "") << p.variance[k];
        os << "]}";
        break;
    }
    return os.str();
}

static std::string extras_json(const Material& m, const BakeSettings& s, const BakeResult& r)
{
    std::ostringstream os;
    os.precision(9);
    os << "{\"jade\":{\"version\":1,\"units\":\"t_m unitless (profile normalised to 1 over the plane); "
          "profile lengths in mesh units\","
       << "\"material\":{\"name\":\"" << m.name << "\",\"albedo\":[" << m.albedo.x << "," << m.albedo.y << ","
       << m.albedo.z << "],\"strength\":" << m.strength << ",\"ior\":" << m.ior << ",\"roughness\":" << m.roughness
       << ",\"profiles\":[" << profile_json(m.profile[0]) << "," << profile_json(m.profile[1]) << ","
       << profile_json(m.profile[2]) << "]},"
       << "\"settings\":{\"ao_rays\":" << s.ao.rays << ",\"ao_low_discrepancy\":" << (s.ao.low_discrepancy ? "true" : "false")
       << ",\"ao_seed\":" << s.ao.seed << ",\"ao_max_distance_rel\":" << s.ao.max_distance_rel
       << ",\"ao_epsilon_rel\":" << s.ao.epsilon_rel << ",\"tm_method\":\"" << tm_method_name(r.method_used)
       << "\",\"tm_epsilon\":" << s.tm_epsilon << "},"
       << "\"timings_ms\":{\"wall\":" << r.timings.wall_ms << ",\"gpu\":" << r.timings.gpu_total_ms;
    for (auto& [stage, ms] : r.timings.gpu_stages) os << ",\"" << stage << "\":" << ms;
    os << "}}}";
    return os.str();
}

int cmd_bake(int argc, char** argv)
{
    auto specs = device_options();
    for (auto& v : {material_options(), bake_options()}) specs.insert(specs.end(), v.begin(), v.end());
    specs.push_back({"out", "FILE", "output .glb or .gltf (required)"});
    Args args("bake", specs, argc, argv, 2);
    if (args.flag("help")) {
        std::printf("usage: jade bake MESH --out FILE.glb [options]\n\nBakes ambient occlusion and the translucency "
                    "magnitude t_m on the GPU and writes the mesh\nwith per-vertex attributes _AO (SCALAR) and _TM (VEC3, "
                    "linear RGB) and the settings in extras.\n\n%s", args.help().c_str());
        return 0;
    }
    if (args.positional().size() != 1) args.fail("expects exactly one MESH");
    auto out = args.get("out");
    if (!out) args.fail("--out FILE is required");
    BakeSettings settings = bake_settings_from_args(args);
    check_output_file(args, "out", *out, {".glb", ".gltf"});

    TriangleMesh mesh = load_mesh_arg(args.positional()[0]);
    PreparedMesh prepared = prepare_mesh(mesh);
    Material material = material_from_args(args, prepared);
    auto ctx = make_context(args);
    if (args.flag("verbose")) std::fprintf(stderr, "jade: device %s\n", ctx->device_info().name.c_str());
    Baker baker(*ctx);
    std::fprintf(stderr, "jade: baking %zu vertices, %u AO rays each, material %s ...\n", prepared.vertex_count(),
                 settings.ao.rays, material.name.c_str());
    BakeResult r = baker.bake(prepared, material, settings);
    for (auto& [stage, ms] : r.timings.gpu_stages) std::fprintf(stderr, "  %-18s %s\n", stage.c_str(), format_ms(ms).c_str());
    std::fprintf(stderr, "  %-18s %s (GPU %s)\n", "total", format_ms(r.timings.wall_ms).c_str(),
                 format_ms(r.timings.gpu_total_ms).c_str());

    BakedAttributes baked;
    baked.ao = to_render_vertices(prepared, r.ao, 0.0f);
    baked.tm = to_render_vertices(prepared, r.tm, glm::vec3(0.0f));
    if (!r.thickness.empty()) baked.thickness = to_render_vertices(prepared, r.thickness, 0.0f);
    baked.extras_json = extras_json(material, settings, r);
    save_baked_gltf(*out, mesh, baked);
    std::printf("wrote %s\n", out->c_str());
    return 0;
}

}  // namespace jade::cli
