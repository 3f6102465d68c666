// jade bench bake MESH: GPU bake timings per stage, measured side by side with the float64 CPU
// reference and the all-pairs GPU pass in one run, and the error of each against float64.
#include "commands.hpp"

#include <jade/io.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace jade::cli {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double max_rel_error(const std::vector<glm::vec3>& gpu, const std::vector<glm::dvec3>& ref, const std::vector<uint32_t>& at)
{
    double e = 0;
    for (size_t k = 0; k < at.size(); ++k)
        for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(gpu[at[k]][c] - ref[k][c]) / std::max(ref[k][c], 1e-12));
    return e;
}

int bench_bake(const Args& args)
{
    TriangleMesh mesh = load_mesh_arg(args.positional().size() > 1 ? args.positional()[1] : "bunny");
    PreparedMesh p = prepare_mesh(mesh);
    Material m = material_from_args(args, p);
    BakeSettings s = bake_settings_from_args(args);
    uint32_t reps = args.count("repeat", 3, 1, 100);
    auto ctx = make_context(args);
    Baker baker(*ctx);
    const double n = double(p.vertex_count());
    std::printf("mesh %s: %zu vertices, %zu triangles; device %s\n", mesh.name.c_str(), p.vertex_count(),
                p.triangle_count(), ctx->device_info().name.c_str());
    std::printf("material %s, %u AO rays, t_m epsilon %g\n\n", m.name.c_str(), s.ao.rays, s.tm_epsilon);

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
        if (stage == "ao") ao_ms += ms;
        else tm_ms += ms;
    }
    std::printf("  %-20s %10s   (wall %s, CPU setup %s)\n", "total", format_ms(best.timings.gpu_total_ms).c_str(),
                format_ms(best.timings.wall_ms).c_str(), format_ms(best.timings.setup_ms).c_str());
    std::printf("  AO rays              %10.2f Mrays/s\n", n * s.ao.rays / (ao_ms * 1e3));

    BakeSettings exact = s;
    exact.method = TmMethod::Exact;
    BakeResult ex = baker.bake_tm(p, best.ao, m, exact);
    double ex_ms = ex.timings.gpu_total_ms;
    std::printf("\nall-pairs GPU t_m     %10s   %.1f Mpairs/s   (clustered is %.1fx faster)\n", format_ms(ex_ms).c_str(),
                n * n / (ex_ms * 1e3), ex_ms / tm_ms);

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
    std::printf("\nmax relative t_m error vs float64 on %zu vertices: clustered %.2e, all-pairs %.2e\n", at.size(),
                max_rel_error(best.tm, ref_tm, at), max_rel_error(ex.tm, ref_tm, at));
    return 0;
}

}  // namespace

int cmd_bench(int argc, char** argv)
{
    auto specs = device_options();
    for (auto& v : {material_options(), bake_options()}) specs.insert(specs.end(), v.begin(), v.end());
    specs.push_back({"repeat", "N", "timed repetitions, best kept (default 3)"});
    specs.push_back({"sample", "N", "vertices the float64 t_m reference runs on (default 256)"});
    Args args("bench", specs, argc, argv, 2);
    if (args.flag("help") || args.positional().empty()) {
        std::printf("usage: jade bench bake [MESH] [options]\n\n%s", args.help().c_str());
        return args.flag("help") ? 0 : 2;
    }
    if (args.positional()[0] == "bake") return bench_bake(args);
    args.fail("unknown benchmark '" + args.positional()[0] + "' (known: bake)");
}

}  // namespace jade::cli
