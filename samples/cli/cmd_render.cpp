// jade render | figure1: images of a mesh with the translucency magnitude (or Lambert,
// curvature-based, false colour, the Filament peer) and the poster's Figure 1.
#include "commands.hpp"
#include "render_setup.hpp"

#include <jade/dev/names.hpp>
#include <jade/io.hpp>
#include <jade/dev/overlay.hpp>
#include <jade/render.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <tuple>

namespace jade::cli {
namespace {
// Copies `panel` into `figure` with its top-left corner at (x0, y0).
void blit(RenderedImage& figure, const RenderedImage& panel, uint32_t x0, uint32_t y0)
{
    for (uint32_t y = 0; y < panel.height; ++y)
        std::copy_n(panel.pixel(0, y), panel.width * 4, figure.pixel(x0, y0 + y));
}

}  // namespace

int cmd_render(int argc, char** argv)
{
    const char* const usage =
        "usage: jade render MESH|BAKED.glb [options]\n\nRenders the mesh with translucency-magnitude "
        "shading (Kubo et al. 2015). A file written by\n`jade bake` (with _TM) renders at once; any other "
        "mesh is baked first (with --material).";
    Args args("render",
              all_options({device_options(), material_options(), bake_options(), input_options(), render_options()}),
              argc, argv, 2);
    if (print_help(args, usage)) return 0;
    if (args.positional().size() > 1) args.fail("expects one MESH");
    RenderSettings settings;
    std::tie(settings.width, settings.height) = parse_size(args, "512x512");
    try {
        settings.mode = dev::parse_shading_mode(args.get_or("mode", "tm"));
    } catch (const Error& e) {
        args.fail(std::string("--mode: ") + e.what());
    }
    try {
        if (args.flag("tonemap")) settings.tone_map = dev::parse_tone_map(args.get_or("tonemap-curve", "aces"));
    } catch (const Error& e) {
        args.fail(std::string("--tonemap-curve: ") + e.what());
    }
    settings.exposure = float(args.number("exposure", 1.0, 0.0, 1e6));
    settings.samples = args.count("samples", 4, 1, 8);
    settings.shadows = !args.flag("no-shadows");
    if (args.get("filament-thickness"))
        settings.filament_thickness = float(args.number("filament-thickness", 0.5, 0.0, 1.0));
    settings.separable_taps = args.count("taps", 17, 11, 25);
    settings.burley_samples = args.count("burley-samples", 40, 1, 80);
    if (settings.separable_taps != 11 && settings.separable_taps != 17 && settings.separable_taps != 25)
        args.fail("--taps: 11, 17 or 25");
    const std::string out = args.get_or("out", "render.png");
    check_output_file(args, "out", out, {".png", ".exr"});

    auto ctx = make_context(args);
    // Filament reads the baked thickness (normalised by the medium: jade::filament_subsurface).
    const bool need_tm = settings.mode == ShadingMode::Tm || settings.mode == ShadingMode::TmFalseColor ||
                         settings.mode == ShadingMode::Filament;
    MeshScene scene = load_scene(args, *ctx, args.positional().empty() ? "bunny" : args.positional()[0], need_tm);
    Camera camera = camera_from_args(args, scene.prepared, float(settings.width) / float(settings.height));
    std::vector<Light> lights = lights_from_args(args, camera);

    Renderer renderer(*ctx, renderer_options(args));
    set_scene(renderer, scene);
    RenderedImage image = renderer.render(camera, lights, settings);
    save_image(out, int(image.width), int(image.height), image.rgba);
    std::printf("%s: %ux%u, %s, material %s, lights: %zu; GPU %s, wall %s\n", out.c_str(), image.width, image.height,
                std::string(dev::shading_mode_name(settings.mode)).c_str(), scene.material.name.c_str(), lights.size(),
                format_ms(image.gpu_ms).c_str(), format_ms(image.wall_ms).c_str());
    return 0;
}

int cmd_figure1(int argc, char** argv)
{
    const auto specs = all_options({device_options(),
                                    material_options(),
                                    bake_options(),
                                    {{"out", "FILE", "output image (default figure1.png)"},
                                     {"size", "WxH", "size of each of the four panels (default 512x512)"},
                                     {"mesh", "MESH", "mesh or baked .glb (default: the Stanford bunny)"},
                                     {"tonemap", "", "tone map the shaded panels with the ACES fit"},
                                     eval_option(),
                                     light_path_option()}});
    Args first("figure1", specs, argc, argv, 2);
    if (print_help(first,
                   "usage: jade figure1 [options]\n\nThe poster's Figure 1: the bunny made of blue jewel under a "
                   "back light, (a) Lambert,\n(b) curvature-based, (c) translucency magnitude (ours), (d) t_m in false "
                   "colour.\n(--material defaults to blue-jewel here.)"))
        return 0;
    if (!first.positional().empty()) first.fail("takes no positional arguments (use --mesh)");
    // The poster's material unless --material is given: parse again with it appended.
    std::vector<std::string> words(argv, argv + argc);
    if (!first.get("material")) words.insert(words.end(), {"--material", "blue-jewel"});
    std::vector<char*> word_ptrs;
    for (auto& w : words) word_ptrs.push_back(w.data());
    Args args("figure1", specs, int(word_ptrs.size()), word_ptrs.data(), 2);
    auto [w, h] = parse_size(args, "512x512");
    const std::string out = args.get_or("out", "figure1.png");
    check_output_file(args, "out", out, {".png", ".exr"});

    auto ctx = make_context(args);
    MeshScene scene = load_scene(args, *ctx, args.get_or("mesh", "bunny"), true);
    Camera camera = Camera::framing(scene.prepared.bbox_min, scene.prepared.bbox_max, float(w) / float(h));
    std::vector<Light> lights = figure1_lights(camera);
    Renderer renderer(*ctx, renderer_options(args));
    set_scene(renderer, scene);

    const int scale = std::max(1, int(h) / 160);
    const uint32_t label_h = uint32_t(14 * scale);
    RenderedImage figure;
    figure.width = 4 * w, figure.height = h + label_h;
    figure.rgba.assign(size_t(figure.width) * figure.height * 4, 0.0f);
    for (size_t i = 3; i < figure.rgba.size(); i += 4) figure.rgba[i] = 1.0f;
    const ShadingMode modes[] = {ShadingMode::Lambert, ShadingMode::Curvature, ShadingMode::Tm,
                                 ShadingMode::TmFalseColor};
    const char* labels[] = {"(a) Lambert", "(b) Curvature-based", "(c) Our method", "(d) Trans. Magnitude"};
    for (int k = 0; k < 4; ++k) {
        RenderSettings s;
        s.width = w, s.height = h, s.mode = modes[k];
        if (args.flag("tonemap") && modes[k] != ShadingMode::TmFalseColor) s.tone_map = ToneMap::AcesFitted;
        RenderedImage panel = renderer.render(camera, lights, s);
        blit(figure, panel, uint32_t(k) * w, 0);
        const int x = int(k * w) + (int(w) - text_width(labels[k], scale)) / 2;
        draw_text(figure, x, int(h) + 3 * scale, labels[k], glm::vec3(1.0f), scale);
        std::printf("(%c) %-16s GPU %s\n", 'a' + k, std::string(dev::shading_mode_name(modes[k])).c_str(),
                    format_ms(panel.gpu_ms).c_str());
    }
    save_image(out, int(figure.width), int(figure.height), figure.rgba);
    std::printf("%s: %ux%u, material %s\n", out.c_str(), figure.width, figure.height, scene.material.name.c_str());
    return 0;
}

}  // namespace jade::cli
