// jade bench render [MESH]: the frame time of every shading mode (Jade's and the peers', docs/
// peers.md) on the same mesh, camera and lights, measured side by side in one run at each size,
// as a ratio to Lambert; each mode's texture fetches per shaded pixel, by construction; and with
// --deform, Jade's per-frame re-bake of a deforming mesh next to them (the peers need none).
#include "commands.hpp"
#include "deform_sweep.hpp"
#include "render_setup.hpp"

#include <jade/dev/material.hpp>
#include <jade/dev/context.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/bake.hpp>
#include <jade/deform.hpp>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <sstream>

namespace jade::cli {
namespace {

// CPU time of the whole process, all threads (lavapipe renders on this process's threads):
// the work done, whatever other jobs on the machine do to the wall time.
double process_cpu_ms()
{
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

/// One timed configuration.
struct Config {
    std::string name;
    ShadingMode mode;
    bool shadows;
};

/// What the lights of a draw ask of the shader: lights, those with a shadow tile, those drawn
/// with transmission (the renderer's rules, docs/shading.md: at most 4 tiles, 4 transmitters).
struct LightLoad {
    uint32_t lights = 0, shadowed = 0, transmitting = 0;
};

/// Texture and buffer fetches per shaded pixel, by construction (the shaders as written; a
/// pixel is one fragment, MSAA shades once per pixel): per light with a shadow tile 9 (shadow.glsl:
/// 3 × 3 taps of the RGBA32F tile, both layers in one fetch), and in tm (soft_shadow_visibility)
/// 5 where the centre and the 4 outermost taps agree, 21 near a
/// shadow's edge (the count below takes the 5); curvature 1 per light (its LUT);
/// tm 3 per light with the LUT paths (1 for a grey material; 0 with the ALU path that lavapipe
/// takes), and per transmitting light 4 depth-tile fetches for the light's path (per fragment; 0
/// with the path per vertex) and 2 of the attenuation table; filament 0 (its thickness is a
/// vertex attribute); separable 1 per light with a tile (its transmittance) and 1 + taps per blur
/// pass, two passes; burley 1 per light with a tile and 1 + samples (docs/peers_separable.md).
/// Returns the count and its formula.
std::pair<uint32_t, std::string> fetches(ShadingMode mode, const LightLoad& l, bool shadows, TmEvaluation eval,
                                         bool grey, dev::LightPathSampling path, const RenderSettings& s)
{
    const bool soft = mode == ShadingMode::Tm;
    const uint32_t shadow = shadows ? (soft ? 5 : 9) * l.shadowed : 0;
    std::string formula = shadows && l.shadowed ? (soft ? "5 (21 at an edge)/shadowed light" : "9/shadowed light") : "";
    auto plus = [&](const std::string& term) { formula += (formula.empty() ? "" : " + ") + term; };
    uint32_t n = shadow;
    if (mode == ShadingMode::Curvature) n += l.lights, plus("1/light");
    if (mode == ShadingMode::Tm) {
        const uint32_t per_light = eval == TmEvaluation::Alu ? 0 : grey ? 1 : 3;
        n += per_light * l.lights;
        if (per_light) plus(std::to_string(per_light) + "/light");
        const uint32_t per_transmitter = path == dev::LightPathSampling::PerVertex ? 2 : 6;
        n += per_transmitter * l.transmitting;
        // The diffused light's gather is per vertex (24 tile fetches and 4 for its path), not in the
        // per-pixel count.
        if (l.transmitting) plus(std::to_string(per_transmitter) + "/transmitting light, 28/vertex");
    }
    if (mode == ShadingMode::Separable || mode == ShadingMode::Burley) {
        n += l.shadowed;
        if (l.shadowed) plus("1/shadowed light");
        const uint32_t blur = mode == ShadingMode::Separable ? 2 * (1 + s.separable_taps) : 1 + s.burley_samples;
        n += blur;
        plus(mode == ShadingMode::Separable ? "2 x (1 + " + std::to_string(s.separable_taps) + " taps)"
                                            : "1 + " + std::to_string(s.burley_samples) + " samples");
    }
    return {n, formula.empty() ? "none" : formula};
}

std::vector<std::pair<uint32_t, uint32_t>> parse_sizes(const Args& args)
{
    std::vector<std::pair<uint32_t, uint32_t>> sizes;
    std::stringstream list(args.get_or("sizes", "512,1920x1080"));
    for (std::string word; std::getline(list, word, ',');) {
        char* end = nullptr;
        const long w = std::strtol(word.c_str(), &end, 10);
        long h = w;
        if (*end == 'x') h = std::strtol(end + 1, &end, 10);
        if (word.empty() || *end != '\0' || w < 1 || w > 16384 || h < 1 || h > 16384)
            args.fail("--sizes: '" + word + "' is not N or WxH in 1..16384");
        sizes.push_back({uint32_t(w), uint32_t(h)});
    }
    if (sizes.empty()) args.fail("--sizes: no size given");
    return sizes;
}

std::vector<Config> configs_from_args(const Args& args)
{
    const bool shadows = !args.flag("no-shadows");
    std::vector<Config> out;
    if (const auto mode = args.get("shadow-cost")) {
        ShadingMode m{};
        try {
            m = dev::parse_shading_mode(*mode);
        } catch (const Error& e) {
            args.fail(std::string("--shadow-cost: ") + e.what());
        }
        return {{std::string(dev::shading_mode_name(m)) + "/noshadow", m, false}, {std::string(*mode), m, true}};
    }
    std::stringstream list(args.get_or("modes", "lambert,curvature,tm,filament,separable,burley"));
    for (std::string word; std::getline(list, word, ',');) {
        ShadingMode m{};
        try {
            m = dev::parse_shading_mode(word);
        } catch (const Error& e) {
            args.fail(std::string("--modes: ") + e.what());
        }
        if (m == ShadingMode::TmFalseColor) args.fail("--modes: tm-false-color is unlit, not a mode to time");
        out.push_back({word + (shadows ? "" : "/noshadow"), m, shadows});
    }
    if (out.empty() || out[0].mode != ShadingMode::Lambert)
        args.fail("--modes: the list starts with lambert (the ratios' base)");
    return out;
}

// --deform: the per-frame cost of keeping a deforming mesh's bake current (DynamicBake, full
// re-bake every frame, `jade bench deform`'s sweep), per frame, stage by stage.
void report_rebake(const Args& args, Context& ctx, const MeshScene& scene, double lambert_ms, uint32_t size)
{
    BakeSettings settings = bake_settings_from_args(args);
    if (!args.get("ao-rays")) settings.ao.rays = 32;  // jade bench deform's per-frame budget
    Baker baker(ctx);
    ProceduralDeformer deformer = ProceduralDeformer::fit(DeformerKind::Twist, scene.prepared, 1);
    deformer.period = 2.0f;
    DeformSweep sweep(ctx, baker, scene.prepared, scene.material, settings, deformer, 4, 1.0 / 15.0);
    const SweepStats st = sweep.run({});
    std::printf("\ndeforming mesh (twist, 4 frames, %u AO rays; jade bench deform): per frame, GPU\n"
                "  deform + normals (every mode)     %10s\n"
                "  Jade's re-bake (refit, AO, t_m)   %10s   = %.2fx lambert's frame at %u^2; the peers need none\n",
                settings.ao.rays, format_ms(st.deform + st.normals).c_str(), format_ms(st.bake()).c_str(),
                st.bake() / lambert_ms, size);
}

}  // namespace

int cmd_bench_render(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {
        {"repeat", "N", "frames per mode and size, in rotating order (default 30)"},
        {"samples", "N", "MSAA samples 1, 2, 4, 8 (default 4, as jade render)"},
        {"lights", "PRESET",
         "default (front key + fill) | figure1 (back light, front key, fill) | back (front key + back light): with a "
         "back light tm draws the transmission term too"},
        {"sizes", "LIST", "image sizes, N (square) or WxH (default 512,1920x1080)"},
        {"modes", "LIST", "the modes timed, lambert first (default lambert,curvature,tm,filament,separable,burley)"},
        {"taps", "N", "separable: taps of each 1-D blur pass, 11 | 17 | 25 (default 17)"},
        {"burley-samples", "N", "burley: samples per pixel, 1..80 (default 40)"},
        {"no-shadows", "", "every mode without shadows"},
        {"shadow-cost", "MODE", "instead of the modes: MODE without shadows against MODE with them"},
        {"deform", "", "also the per-frame re-bake of the mesh deforming (twist), next to the frame times"},
        eval_option(),
        light_path_option()};
    const char* const usage =
        "usage: jade bench render [MESH] [options]\n\nFrame time of every shading mode (Jade's and the peers') "
        "against Lambert at 512x512\nand 1920x1080, the same scene, measured side by side in one run (GPU "
        "timestamps, wall\ntime, and the CPU time of the process, which is lavapipe's work when the machine is\n"
        "shared), with each mode's texture fetches per shaded pixel by construction.";
    Args args("bench render", all_options({device_options(), material_options(), bake_options(), own}), argc, argv, 3);
    if (print_help(args, usage)) return 0;
    const uint32_t repeat = args.count("repeat", 30, 1, 10000);
    const uint32_t samples = args.count("samples", 4, 1, 8);
    const auto sizes = parse_sizes(args);
    const uint32_t taps = args.count("taps", 17, 11, 25), burley_samples = args.count("burley-samples", 40, 1, 80);
    if (taps != 11 && taps != 17 && taps != 25) args.fail("--taps: 11, 17 or 25");
    const std::vector<Config> config = configs_from_args(args);
    auto ctx = make_context(args);
    MeshScene scene = load_scene(args, *ctx, args.positional().empty() ? "bunny" : args.positional()[0], true);
    Camera camera = Camera::framing(scene.prepared.bbox_min, scene.prepared.bbox_max);
    const std::vector<Light> lights = preset_lights(args, camera);
    Renderer renderer(*ctx, renderer_options(args));
    set_scene(renderer, scene);
    const bool thickness = !scene.thickness.empty() || !scene.mesh.baked_thickness.empty();
    const bool transmits = scene.material.transmission.enabled() && thickness;
    std::printf(
        "mesh %s: %zu vertices, %zu triangles; material %s (%s; transmission %s); tm evaluation %s, light path per %s; "
        "device %s\n",
        scene.mesh.name.c_str(), scene.prepared.vertex_count(), scene.prepared.triangle_count(),
        scene.material.name.c_str(), dev::is_grey(scene.material) ? "grey: 1 channel" : "RGB: 3 channels",
        transmits ? "on where a light is behind" : "off",
        std::string(tm_evaluation_name(dev::tm_evaluation(renderer))).c_str(),
        std::string(dev::light_path_sampling_name(dev::light_path(renderer))).c_str(),
        dev::device_info(*ctx).name.c_str());
    // The presets' lights are all directional (each gets a tile); figure1 and back have one light behind.
    const std::string preset = args.get_or("lights", "default");
    const LightLoad load{uint32_t(lights.size()), uint32_t(std::min<size_t>(lights.size(), 4)),
                         transmits && preset != "default" ? 1u : 0u};
    std::printf("same camera, %zu lights (%s: %u shadowed, %u transmitting in tm), %ux MSAA, RGBA16F target, specular "
                "on in every mode; %u frames per mode and size in rotating order after 2 warm-up rounds\n",
                lights.size(), preset.c_str(), load.shadowed, load.transmitting, samples, repeat);
    const std::string base = config[0].name;
    std::printf("%-10s %-18s %11s %11s %21s %21s %8s  %s\n", "size", "mode", "GPU median", "GPU min",
                ("GPU / " + base + " (quart.)").c_str(), ("CPU / " + base + " (quart.)").c_str(), "fetches",
                "fetches per shaded pixel, by construction");
    double lambert_512 = 0;
    uint32_t lambert_size = 0;
    // The machine may be shared: each iteration renders every mode back to back, in rotating
    // order so none always runs first, and the ratio to the first mode is taken per iteration, so
    // load that changes more slowly than one iteration cancels. Quartiles say how noisy it was.
    for (const auto& [width, height] : sizes) {
        RenderSettings s;
        s.width = width, s.height = height;
        s.samples = samples;
        s.separable_taps = taps, s.burley_samples = burley_samples;
        const size_t n = config.size();
        std::vector<std::vector<double>> gpu(n), cpu(n), gpu_ratio(n), cpu_ratio(n);
        for (int warm = 0; warm < 2; ++warm)  // pipelines, targets, caches
            for (const Config& c : config) s.mode = c.mode, s.shadows = c.shadows, renderer.render(camera, lights, s);
        for (uint32_t i = 0; i < repeat; ++i) {
            for (size_t j = 0; j < n; ++j) {
                const size_t k = (j + i) % n;
                s.mode = config[k].mode, s.shadows = config[k].shadows;
                const double cpu0 = process_cpu_ms();
                RenderedImage img = renderer.render(camera, lights, s);
                cpu[k].push_back(process_cpu_ms() - cpu0);
                gpu[k].push_back(img.gpu_ms);
            }
            for (size_t k = 0; k < n; ++k) {
                gpu_ratio[k].push_back(gpu[k].back() / gpu[0].back());
                cpu_ratio[k].push_back(cpu[k].back() / cpu[0].back());
            }
        }
        for (size_t k = 0; k < n; ++k) {
            const auto [count, formula] = fetches(config[k].mode, load, config[k].shadows, dev::tm_evaluation(renderer),
                                                  dev::is_grey(scene.material), dev::light_path(renderer), s);
            char size[32], ratio[64], cpu_r[64];
            std::snprintf(size, sizeof size, "%ux%u", width, height);
            std::snprintf(ratio, sizeof ratio, "%.3fx (%.2f-%.2f)", quantile(gpu_ratio[k], 0.5),
                          quantile(gpu_ratio[k], 0.25), quantile(gpu_ratio[k], 0.75));
            std::snprintf(cpu_r, sizeof cpu_r, "%.3fx (%.2f-%.2f)", quantile(cpu_ratio[k], 0.5),
                          quantile(cpu_ratio[k], 0.25), quantile(cpu_ratio[k], 0.75));
            std::printf("%-10s %-18s %11s %11s %21s %21s %8u  %s\n", size, config[k].name.c_str(),
                        format_ms(quantile(gpu[k], 0.5)).c_str(), format_ms(quantile(gpu[k], 0.0)).c_str(), ratio,
                        cpu_r, count, formula.c_str());
        }
        std::fflush(stdout);
        if (lambert_size == 0) lambert_512 = quantile(gpu[0], 0.5), lambert_size = width;
    }
    if (args.flag("deform")) report_rebake(args, *ctx, scene, lambert_512, lambert_size);
    return 0;
}

}  // namespace jade::cli
