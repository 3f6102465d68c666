// jade bench bake MESH: GPU bake timings per stage, measured side by side with the float64 CPU
// reference and the all-pairs GPU pass in one run, and the error of each against float64.
// jade bench render --scene SCENE.gltf: frame time of a cached static scene against the same
// scene never baked (t_m = 0: the same draws), measured alternately in one run.
#include "commands.hpp"
#include "embree_ao.hpp"

#include <jade/dev/bake.hpp>
#include <jade/dev/cache.hpp>
#include <jade/dev/context.hpp>
#include <jade/dev/clock.hpp>
#include <jade/dev/names.hpp>
#include <jade/io.hpp>
#include <jade/dev/reference.hpp>
#include <jade/dev/scene.hpp>
#include <jade/scene.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace jade::cli {
namespace {

double max_rel_error(const std::vector<glm::vec3>& gpu, const std::vector<glm::dvec3>& ref,
                     const std::vector<uint32_t>& at)
{
    double e = 0;
    for (size_t k = 0; k < at.size(); ++k)
        for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(gpu[at[k]][c] - ref[k][c]) / std::max(ref[k][c], 1e-12));
    return e;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// The clustered and the grid far fields, alternately on the same AO, `pairs` times: GPU time of
// the t_m passes, the median of the per-pair ratios, memory, and each one's error.
void compare_far_fields(Baker& baker, const PreparedMesh& p, const std::vector<float>& ao, const Material& m,
                        const BakeSettings& s, uint32_t pairs, const std::vector<glm::dvec3>& ref,
                        const std::vector<uint32_t>& at)
{
    BakeSettings clustered = s, grid = s;
    clustered.method = TmMethod::Clustered;
    grid.method = TmMethod::Grid;
    dev::bake_tm(baker, p, ao, m, grid);  // warm-up: the grid pipelines
    std::vector<double> tc, tg, ratio;
    BakeResult rc, rg;
    for (uint32_t i = 0; i < pairs; ++i) {
        rc = dev::bake_tm(baker, p, ao, m, clustered);
        rg = dev::bake_tm(baker, p, ao, m, grid);
        tc.push_back(rc.timings.gpu_total_ms);
        tg.push_back(rg.timings.gpu_total_ms);
        ratio.push_back(tc.back() / tg.back());
    }
    std::printf("\nt_m far field, clustered (theta %g) and grid (resolution %g), %u alternating runs (GPU time of all "
                "t_m passes, median):\n",
                double(s.tm_opening_ratio), double(s.tm_grid_resolution), pairs);
    std::printf("  clustered  %10s   %7.2f MiB   max rel error %.2e\n", format_ms(median(tc)).c_str(),
                double(rc.tm_bytes) / 1048576.0, max_rel_error(rc.tm, ref, at));
    std::printf("  grid       %10s   %7.2f MiB   max rel error %.2e\n", format_ms(median(tg)).c_str(),
                double(rg.tm_bytes) / 1048576.0, max_rel_error(rg.tm, ref, at));
    std::printf("  grid is %.2fx faster (median of the per-run ratios)\n  grid stages:", median(ratio));
    for (auto& [stage, ms] : rg.timings.gpu_stages) std::printf(" %s %s;", stage.c_str(), format_ms(ms).c_str());
    std::printf("\n");
}

int bench_bake(const Args& args)
{
    TriangleMesh mesh = load_mesh_arg(args.positional().size() > 1 ? args.positional()[1] : "bunny");
    PreparedMesh p = prepare_mesh(mesh);
    Material m = material_from_args(args, p);
    BakeSettings s = bake_settings_from_args(args);
    uint32_t reps = args.count("repeat", 3, 1, 100);  // render --scene: frame pairs, default 30
    auto ctx = make_context(args);
    Baker baker(*ctx);
    const double n = double(p.vertex_count());
    std::printf("mesh %s: %zu vertices, %zu triangles; device %s\n", mesh.name.c_str(), p.vertex_count(),
                p.triangle_count(), dev::device_info(*ctx).name.c_str());
    std::printf("material %s, %u AO rays, t_m epsilon %g\n\n", m.name.c_str(), s.ao.rays, s.tm_opening_ratio);

    baker.bake(p, m, s);  // warm-up: pipelines, caches
    BakeResult best;
    for (uint32_t i = 0; i < reps; ++i) {
        BakeResult r = baker.bake(p, m, s);
        if (i == 0 || r.timings.wall_ms < best.timings.wall_ms) best = r;
    }
    double ao_ms = 0, tm_ms = 0;
    std::printf("GPU bake, best of %u (GPU time per stage):\n", reps);
    for (auto& [stage, ms] : best.timings.gpu_stages) {
        std::printf("  %-20s %10s\n", stage.c_str(), format_ms(ms).c_str());
        if (stage == "ao")
            ao_ms += ms;
        else
            tm_ms += ms;
    }
    std::printf("  %-20s %10s   (wall %s, CPU setup %s)\n", "total", format_ms(best.timings.gpu_total_ms).c_str(),
                format_ms(best.timings.wall_ms).c_str(), format_ms(best.timings.setup_ms).c_str());
    std::printf("  AO rays              %10.2f Mrays/s\n", n * s.ao.rays / (ao_ms * 1e3));

    BakeSettings exact = s;
    exact.method = TmMethod::Exact;
    BakeResult ex = dev::bake_tm(baker, p, best.ao, m, exact);
    double ex_ms = ex.timings.gpu_total_ms;
    std::printf("\nall-pairs GPU t_m     %10s   %.1f Mpairs/s   (clustered is %.1fx faster)\n",
                format_ms(ex_ms).c_str(), n * n / (ex_ms * 1e3), ex_ms / tm_ms);

    // float64 CPU reference: AO on every vertex, t_m on a sample (scaled to all vertices).
    auto t0 = Clock::now();
    auto ref_ao = reference_ao(p, s.ao);
    double cpu_ao_ms = ms_since(t0);
    size_t same = 0;
    for (size_t i = 0; i < ref_ao.size(); ++i) same += ref_ao[i] == best.ao[i];
    std::vector<uint32_t> at;
    size_t sample = std::min<size_t>(p.vertex_count(), args.count("sample", 256, 1, 1u << 30));
    for (size_t k = 0; k < sample; ++k) at.push_back(uint32_t(k * p.vertex_count() / sample));
    t0 = Clock::now();
    auto ref_tm = reference_tm(p, best.ao, m, at);
    double cpu_tm_ms = ms_since(t0) * n / double(at.size());
    std::printf("float64 CPU AO        %10s   (GPU is %.1fx faster; %.3f%% of vertices identical)\n",
                format_ms(cpu_ao_ms).c_str(), cpu_ao_ms / ao_ms, 100.0 * same / n);
    std::printf("float64 CPU t_m       %10s   (extrapolated from %zu vertices; GPU clustered is %.0fx faster)\n",
                format_ms(cpu_tm_ms).c_str(), at.size(), cpu_tm_ms / tm_ms);
    std::printf("\n");
    compare_ao_with_embree(baker, p, s.ao, std::max(5u, reps));
    std::printf("\nmax relative t_m error vs float64 on %zu vertices: %s %.2e, all-pairs %.2e\n", at.size(),
                dev::tm_method_name(best.method_used), max_rel_error(best.tm, ref_tm, at),
                max_rel_error(ex.tm, ref_tm, at));
    compare_far_fields(baker, p, best.ao, m, s, std::max(5u, reps), ref_tm, at);
    return 0;
}

int bench_render_scene(const Args& args)
{
    std::vector<std::string> warnings;
    const Scene scene = load_scene(*args.get("scene"), &warnings);
    for (const auto& w : warnings) std::fprintf(stderr, "jade: warning: %s\n", w.c_str());
    for (const auto& o : scene.objects)
        if (o.deformer) args.fail("--scene: object '" + o.name + "' deforms; the benchmark compares static scenes");
    SceneSettings settings = scene_settings_from_args(args);
    const std::filesystem::path dir =
        args.get_or("cache", (std::filesystem::temp_directory_path() / "jade-bench-cache").string());
    const dev::BakeCache cache(dir);
    const uint32_t repeat = args.count("repeat", 30, 1, 10000);
    RenderSettings rs;
    rs.width = rs.height = args.count("size", 512, 1, 16384);
    rs.samples = args.count("samples", 4, 1, 8);
    auto ctx = make_context(args);
    {
        SceneRenderer fill(*ctx, scene, settings, dev::cached_bakes(cache));  // bakes what the cache lacks
        size_t baked = 0;
        for (const auto& p : dev::passes_run(fill)) baked += p.kind == dev::PassKind::StaticBake;
        std::printf("cache %s: %zu static bakes were missing and ran now\n", dir.string().c_str(), baked);
    }
    const ObjectCounts before = dev::created_objects(*ctx);
    SceneRenderer cached(*ctx, scene, settings, dev::cached_bakes(cache));
    const ObjectCounts after = dev::created_objects(*ctx);
    SceneRenderer unbaked(*ctx, scene, settings, dev::never_baked());
    std::printf(
        "cached scene set-up created %llu compute pipelines (%zu objects: the one shared LUT's builder and each "
        "transmitting object's attenuation table, no bake kernel) and %llu buffers (%.2f MiB device-local: the draws' "
        "only)\n",
        (unsigned long long)(after.compute_pipelines - before.compute_pipelines), scene.objects.size(),
        (unsigned long long)(after.buffers - before.buffers),
        double(after.device_buffer_bytes - before.device_buffer_bytes) / double(1u << 20));
    std::printf("scene %s: %zu objects; %ux%u, %ux MSAA, %u iterations of one frame each (rotating order) after 2 "
                "warm-up ones, device %s\n",
                scene.name.c_str(), scene.objects.size(), rs.width, rs.height, rs.samples, repeat,
                dev::device_info(*ctx).name.c_str());
    const Camera camera = Camera::framing(cached.bbox_min(), cached.bbox_max(), 1.0f, glm::vec3(0.35f, 0.45f, 1.0f));
    const auto lights = default_lights(camera);
    // For reference only: every material opaque (Lambert, no t_m at all).
    Scene lambert_scene = scene;
    for (auto& o : lambert_scene.objects) o.material.opaque = true;
    SceneRenderer lambert(*ctx, lambert_scene, settings);
    SceneRenderer* r[3] = {&unbaked, &cached, &lambert};
    std::vector<double> gpu[3], wall[3], gpu_ratio, wall_ratio;
    for (int warm = 0; warm < 2; ++warm)
        for (auto* x : r) x->render(0.0, camera, lights, rs);
    for (uint32_t i = 0; i < repeat; ++i) {
        for (int n = 0; n < 3; ++n) {  // rotating order: none always runs first or last
            const int k = (n + int(i)) % 3;
            const RenderedImage img = r[k]->render(0.0, camera, lights, rs);
            gpu[k].push_back(img.gpu_ms);
            wall[k].push_back(img.wall_ms);
        }
        gpu_ratio.push_back(gpu[1].back() / gpu[0].back());
        wall_ratio.push_back(wall[1].back() / wall[0].back());
    }
    std::printf("%-26s %12s %12s %12s %12s\n", "scene", "GPU median", "GPU min", "wall median", "wall min");
    const char* names[3] = {"never baked (tm, t_m = 0)", "cached static bake (tm)", "all opaque (lambert)"};
    for (int k = 0; k < 3; ++k)
        std::printf("%-26s %12s %12s %12s %12s\n", names[k], format_ms(quantile(gpu[k], 0.5)).c_str(),
                    format_ms(quantile(gpu[k], 0.0)).c_str(), format_ms(quantile(wall[k], 0.5)).c_str(),
                    format_ms(quantile(wall[k], 0.0)).c_str());
    std::printf("cached / never baked: GPU %.3fx (median of %u per-iteration ratios; quartiles %.3f-%.3f), wall %.3fx "
                "(quartiles %.3f-%.3f); target: within 5%%\n",
                quantile(gpu_ratio, 0.5), repeat, quantile(gpu_ratio, 0.25), quantile(gpu_ratio, 0.75),
                quantile(wall_ratio, 0.5), quantile(wall_ratio, 0.25), quantile(wall_ratio, 0.75));
    std::printf("cached / all opaque (reference, the price of t_m shading): GPU %.3fx (ratio of medians)\n",
                quantile(gpu[1], 0.5) / quantile(gpu[2], 0.5));
    return 0;
}

}  // namespace

int cmd_bench(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {
        {"repeat", "N", "timed repetitions, best kept (default 3)"},
        {"sample", "N", "vertices the float64 t_m reference runs on (default 256)"},
        {"scene", "FILE", "render: a static glTF scene, cached against never baked"},
        {"cache", "DIR", "render --scene: the bake cache (default: the system's temp folder)"},
        {"mode", "M", "render --scene: tm | tm-false-color (default tm)"},
        {"size", "N", "render --scene: square image size (default 512)"},
        {"samples", "N", "render --scene: MSAA samples (default 4)"}};
    Args args("bench", all_options({device_options(), material_options(), bake_options(), own}), argc, argv, 2);
    if (args.flag("help") || args.positional().empty()) {
        print_usage(args, "usage: jade bench bake [MESH] [options]\n"
                          "       jade bench render --scene SCENE.gltf [--cache DIR] [options]");
        return args.flag("help") ? 0 : 2;
    }
    if (args.positional()[0] == "bake") return bench_bake(args);
    if (args.positional()[0] == "render" && args.get("scene")) return bench_render_scene(args);
    args.fail("unknown benchmark '" + args.positional()[0] + "' (known: bake, render --scene)");
}

}  // namespace jade::cli
