// jade bake MESH --out FILE.glb: AO, t_m and the thickness on the GPU, written on the render
// vertices. A glTF input is written back whole with the attributes added (bake_asset.cpp).
#include "bake_record.hpp"
#include "commands.hpp"

#include <jade/dev/context.hpp>
#include <jade/io.hpp>
#include <jade/dev/mesh.hpp>

#include <cstdio>
#include <sstream>

namespace jade::cli {

namespace {

void print_timings(const BakeResult& r)
{
    for (auto& [stage, ms] : r.timings.gpu_stages)
        std::fprintf(stderr, "  %-18s %s\n", stage.c_str(), format_ms(ms).c_str());
    std::fprintf(stderr, "  %-18s %s (GPU %s)\n", "total", format_ms(r.timings.wall_ms).c_str(),
                 format_ms(r.timings.gpu_total_ms).c_str());
}

/// An OFF, PLY or OBJ mesh: one bake, written as a new glTF of that mesh alone.
void bake_mesh(const Args& args, const std::string& in, const std::filesystem::path& out, const BakeSettings& settings)
{
    TriangleMesh mesh = load_mesh_arg(in, read_options(args));
    Material material = material_from_args(args, diagonal(mesh));
    auto ctx = make_context(args);
    if (args.flag("verbose")) std::fprintf(stderr, "jade: device %s\n", dev::device_info(*ctx).name.c_str());
    Baker baker(*ctx);
    std::fprintf(stderr, "jade: baking %zu vertices, %u AO rays each, material %s ...\n", mesh.positions.size(),
                 settings.ao.rays, material.name.c_str());
    PreparedMesh prepared;
    BakeResult r = bake_at_unit_scale(baker, mesh, material, settings, prepared);
    print_timings(r);

    BakedAttributes baked;
    baked.ao = dev::to_render_vertices(prepared, r.ao, 0.0f);
    baked.tm = dev::to_render_vertices(prepared, r.tm, glm::vec3(0.0f));
    if (!r.thickness.empty()) baked.thickness = dev::to_render_vertices(prepared, r.thickness, 0.0f);
    if (!r.scattering_normal.empty()) {
        baked.scattering_normal = dev::to_render_vertices(prepared, r.scattering_normal, glm::vec3(0.0f, 0.0f, 1.0f));
        baked.normal_spread = dev::to_render_vertices(prepared, r.normal_spread, glm::vec3(0.0f));
    }
    baked.material = material;
    std::ostringstream os;
    os << "{\"jade\":{\"version\":1," << record::units() << ",\"material\":" << record::material(material)
       << ",\"settings\":" << record::settings(settings, r) << ",\"timings_ms\":" << record::timings(r) << "}}";
    baked.extras_json = os.str();
    save_baked_gltf(out, mesh, baked);
}

bool is_gltf(const std::filesystem::path& path)
{
    auto ext = path.extension().string();
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".gltf" || ext == ".glb";
}

}  // namespace

int cmd_bake(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {{"out", "FILE", "output .glb or .gltf (required unless --in-place)"},
                                         {"in-place", "",
                                          "replace the glTF input itself (atomically: the old or the new file, never "
                                          "half)"}};
    Args args("bake", all_options({device_options(), material_options(), bake_options(), input_options(), own}), argc,
              argv, 2);
    if (print_help(args,
                   "usage: jade bake MESH --out FILE.glb|.gltf [options]\n"
                   "       jade bake ASSET.gltf|.glb --in-place [options]\n\n"
                   "Bakes ambient occlusion, the translucency magnitude t_m and (for materials with transmission)\n"
                   "the thickness on the GPU and writes them as per-vertex attributes _AO (SCALAR), _TM (VEC3,\n"
                   "linear RGB) and _THICKNESS (SCALAR, mesh units), with the settings in the asset's extras.\n"
                   "A glTF input is written back whole (scenes, nodes, materials, textures, skins, animations,\n"
                   "morph targets, cameras, extensions, extras) with the attributes added to each triangle\n"
                   "primitive; each mesh is baked once, in the world space of its first instance (a skinned\n"
                   "mesh in its bind pose); see docs/gltf.md. Other meshes (.off, .ply, .obj) become a glTF of\n"
                   "the mesh alone."))
        return 0;
    if (args.positional().size() != 1) args.fail("expects exactly one MESH");
    const std::string in = args.positional()[0];
    const bool in_place = args.flag("in-place");
    auto out_arg = args.get("out");
    if (!out_arg && !in_place) args.fail("--out FILE is required (or --in-place to replace a glTF input)");
    if (in_place && !is_gltf(in)) args.fail("--in-place: " + in + " is not a glTF file (.gltf, .glb)");
    std::error_code ec;
    // The input is looked at before its path is resolved: a missing file or a dangling link is
    // the user's mistake to be named, not an internal error.
    if (!std::filesystem::exists(in, ec)) {
        const bool dangling = std::filesystem::is_symlink(std::filesystem::symlink_status(in, ec));
        throw Error(
            std::filesystem::path(in).filename().string() + ": cannot open: " +
            (dangling ? "a symbolic link to a file that does not exist (" + in + ")" : "file not found (" + in + ")"));
    }
    const bool same = out_arg && std::filesystem::exists(*out_arg, ec) && std::filesystem::equivalent(in, *out_arg, ec);
    if (in_place && out_arg && !same)
        args.fail("--in-place replaces " + in + "; --out " + *out_arg + " names another file");
    if (same && !in_place) args.fail("--out " + *out_arg + " is the input file; give --in-place to replace it");
    // In place, the file a link points to is replaced, not the link.
    const std::filesystem::path out = in_place ? std::filesystem::canonical(in, ec) : std::filesystem::path(*out_arg);
    if (ec) throw Error(in + ": cannot resolve the path to replace: " + ec.message());
    BakeSettings settings = bake_settings_from_args(args);
    check_output_file(args, in_place ? "in-place" : "out", out, {".glb", ".gltf"});

    if (is_gltf(in))
        bake_asset(args, in, out, settings);
    else
        bake_mesh(args, in, out, settings);
    std::printf("wrote %s\n", out.string().c_str());
    return 0;
}

}  // namespace jade::cli
