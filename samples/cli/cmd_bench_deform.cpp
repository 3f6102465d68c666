// jade bench deform [MESH...]: frames per second of the per-frame GPU re-bake of a deforming
// mesh (jade::DynamicBake after a MeshDeformer), with the GPU time of each stage, and the
// amortised modes (jade::Amortisation) with the error they add. Every mode plays the same
// animation frames; the error of each frame is measured against a from-scratch bake of that
// deformed frame (jade::Baker::bake on the deformed mesh: a new BVH and cluster tree, the same
// settings), so "full" shows what refitting costs in accuracy and the amortised rows what
// re-baking a part per frame adds to it.
#include <jade/dev/context.hpp>
#include <jade/dev/names.hpp>
#include "commands.hpp"
#include "embree_ao.hpp"
#include "deform_sweep.hpp"

#include <cstdio>
#include <sstream>

namespace jade::cli {
namespace {

std::vector<uint32_t> parse_slices(const Args& args)
{
    std::vector<uint32_t> out;
    std::stringstream in(args.get_or("slices", "2,4,8"));
    for (std::string word; std::getline(in, word, ',');) {
        char* end = nullptr;
        const unsigned long v = std::strtoul(word.c_str(), &end, 10);
        if (word.empty() || *end || v < 2 || v > 64) args.fail("--slices: '" + word + "' is not a count in 2..64");
        out.push_back(uint32_t(v));
    }
    return out;
}

void bench_mesh(const Args& args, Context& ctx, const std::string& path, const std::vector<uint32_t>& slice_counts)
{
    const TriangleMesh mesh = load_mesh_arg(path);
    const PreparedMesh rest = prepare_mesh(mesh);
    const Material material = material_from_args(args, rest);
    BakeSettings settings = bake_settings_from_args(args);
    if (!args.get("ao-rays"))
        settings.ao.rays = 32;  // a per-frame budget: 32 rays keep a re-bake within a frame or two
    DeformerKind kind{};
    try {
        kind = dev::parse_deformer(args.get_or("deformer", "twist"));
    } catch (const Error& e) {
        args.fail(std::string("--deformer: ") + e.what());
    }
    const uint32_t frames = args.count("frames", 8, 2, 1000);
    const double step = 1.0 / args.number("fps", 15.0, 1e-3, 1e4);  // animation seconds per frame
    const uint32_t size = args.count("size", 512, 16, 4096);

    ProceduralDeformer deformer_params = ProceduralDeformer::fit(kind, rest, 1);
    deformer_params.period = 2.0f;
    Baker baker(ctx);
    Renderer renderer(ctx);
    renderer.set_material(material);

    std::printf(
        "\n%s: %zu bake vertices, %zu triangles; %s, %u frames of %.3g s; material %s, %u AO rays, theta %.2g\n",
        mesh.name.c_str(), rest.vertex_count(), rest.triangle_count(), args.get_or("deformer", "twist").c_str(), frames,
        step, material.name.c_str(), settings.ao.rays, settings.tm_opening_ratio);
    // The clustered and the grid far fields, full re-bakes, alternately (two rounds each).
    BakeSettings clustered = settings, grid = settings;
    clustered.method = TmMethod::Clustered;
    grid.method = TmMethod::Grid;
    DeformSweep sweep_clustered(ctx, baker, rest, material, clustered, deformer_params, frames, step);
    DeformSweep sweep_grid(ctx, baker, rest, material, grid, deformer_params, frames, step);
    std::printf("from-scratch bake of each frame (CPU BVH + cluster tree builds, GPU bake): GPU %.1f ms, wall %.1f ms "
                "(clustered), GPU %.1f ms, wall %.1f ms (grid)\n",
                sweep_clustered.rebuild_gpu_ms(), sweep_clustered.rebuild_wall_ms(), sweep_grid.rebuild_gpu_ms(),
                sweep_grid.rebuild_wall_ms());
    std::printf("%-22s %7s %7s %7s %8s %8s %7s %8s %6s | %8s %8s %9s %9s\n", "mode (GPU ms/frame)", "deform", "normals",
                "refit", "AO", "t_m", "draw", "total", "fps", "AO rms", "AO max", "t_m rms", "t_m max");
    auto print = [](const std::string& label, const SweepStats& st) {
        std::printf("%-22s %7.2f %7.2f %7.2f %8.1f %8.1f %7.2f %8.1f %6.2f | %8.4f %8.4f %9.2e %9.2e\n", label.c_str(),
                    st.deform, st.normals, st.refit, st.ao, st.tm, st.draw, st.total(), 1000.0 / st.total(),
                    st.error.ao_rms, st.error.ao_max, st.error.tm_rms, st.error.tm_max);
        std::fflush(stdout);
    };
    SweepStats by_clustered, by_grid;
    double frame_ratio = 0, bake_ratio = 0;
    for (int round = 0; round < 2; ++round) {
        by_clustered = sweep_clustered.run({}, &renderer, size);
        by_grid = sweep_grid.run({}, &renderer, size);
        frame_ratio += 0.5 * by_clustered.total() / by_grid.total();
        bake_ratio += 0.5 * by_clustered.bake() / by_grid.bake();
    }
    print("full, clustered", by_clustered);
    print("full, grid", by_grid);
    std::printf(
        "%-22s the grid's frames are %.2fx faster, its re-bakes %.2fx, its t_m stage %.2fx (mean of 2 rounds)\n", "",
        frame_ratio, bake_ratio, by_clustered.tm / by_grid.tm);
    std::printf("for scale, the rest pose's ");
    compare_ao_with_embree(baker, rest, settings.ao, 3);
    // Amortised modes with the method the settings choose (auto: the grid, docs/bake.md).
    const bool uses_clustered = settings.method == TmMethod::Clustered;
    DeformSweep& sweep = uses_clustered ? sweep_clustered : sweep_grid;
    const SweepStats& full = uses_clustered ? by_clustered : by_grid;
    for (uint32_t s : slice_counts) {
        const std::string label = "amortised 1/" + std::to_string(s);
        if (settings.ao.rays % s != 0) {
            std::printf("%-22s (skipped: %u AO rays are not divisible by %u)\n", label.c_str(), settings.ao.rays, s);
            continue;
        }
        // Amortisation::retrace_changed (the default), then one AO slice a frame whatever moved.
        for (const bool retrace : {true, false}) {
            const SweepStats a = sweep.run({s, s, retrace}, &renderer, size);
            print(retrace ? label : label + ", 1 slice", a);
            std::printf("%-22s %.2fx faster than full; added error AO rms %+.4f, t_m rms %+.2e\n", "",
                        full.total() / a.total(), a.error.ao_rms - full.error.ao_rms,
                        a.error.tm_rms - full.error.tm_rms);
        }
    }
}

}  // namespace

int cmd_bench_deform(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {
        {"deformer", "D", "bend | twist | squash | wave (default twist)"},
        {"frames", "N", "frames per mode (default 8; the first of an amortised mode is a full re-bake)"},
        {"fps", "F", "animation frames per second: each frame advances 1/F s of a 2 s cycle (default 15)"},
        {"slices", "LIST", "amortised modes: AO and t_m slices per mode, e.g. 2,4,8 (default)"},
        {"size", "N", "draw size in pixels, N x N (default 512)"}};
    const char* const usage =
        "usage: jade bench deform [MESH...] [options]\n\nFrames per second of deform + full GPU re-bake + "
        "draw (default: the bunny and the dragon, 32 AO rays,\ndefault quality), the GPU time per stage, and "
        "amortised re-bakes with the error each adds\nagainst a from-scratch bake of every frame.";
    Args args("bench deform", all_options({device_options(), material_options(), bake_options(), own}), argc, argv, 3);
    if (print_help(args, usage)) return 0;
    const std::vector<uint32_t> slices = parse_slices(args);
    std::vector<std::string> meshes = args.positional();
    if (meshes.empty()) {
        const std::filesystem::path dragon = find_asset("ChineseDragon-10kv.off");
        meshes = {"bunny", dragon.empty() ? std::string("assets/ChineseDragon-10kv.off") : dragon.string()};
    }
    auto ctx = make_context(args);
    std::printf("jade bench deform on %s\n", dev::device_info(*ctx).name.c_str());
    for (const auto& path : meshes) bench_mesh(args, *ctx, path, slices);
    return 0;
}

}  // namespace jade::cli
