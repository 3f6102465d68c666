// jade render | figure1 | bench render: images of a mesh with the translucency magnitude
// (or Lambert, curvature-based, false colour), the poster's Figure 1, and the frame-time
// comparison of t_m shading against Lambert.
#include "commands.hpp"

#include <jade/io.hpp>
#include <jade/overlay.hpp>
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

OptionSpec eval_option()
{
    return {"eval", "PATH",
            "how tm evaluates the translucency: auto (by the device) | alu | lut | lut16 (docs/shading.md)"};
}

OptionSpec light_path_option()
{
    return {"light-path", "WHERE",
            "where tm reads a back light's path through the object: auto (by the mesh's resolution) | vertex | "
            "fragment (docs/shading.md)"};
}

std::vector<OptionSpec> render_options()
{
    return {{"mode", "M", "lambert | curvature | tm | tm-false-color | separable | burley (default tm)"},
            {"taps", "N", "separable: taps of each 1-D blur pass, 11 | 17 | 25 (default 17)"},
            {"burley-samples", "N", "burley: samples per pixel, 1..80 (default 40)"},
            {"out", "FILE", "output .png (sRGB, 8 bit) or .exr (linear half float); default render.png"},
            {"size", "WxH", "image size in pixels (default 512x512)"},
            {"eye", "X,Y,Z", "camera position, mesh units (default: framed, see --frame)"},
            {"target", "X,Y,Z", "point looked at (default: the centre of the mesh's bounds)"},
            {"up", "X,Y,Z", "camera up (default 0,1,0)"},
            {"fov", "DEG", "vertical field of view in degrees (default 30)"},
            {"frame", "", "move the eye so the mesh fills the view, seen from --eye's direction (default +z)"},
            {"light", "SPEC",
             "dir:X,Y,Z:R,G,B (towards the light, irradiance) or point:X,Y,Z:R,G,B "
             "(position, intensity); repeatable; replaces --lights"},
            {"lights", "PRESET",
             "default (key upper front-left + fill) | figure1 (back light: ears glow) | back (key + back light)"},
            {"tonemap", "", "tone map with the ACES fit (default: linear HDR, clipped by the PNG)"},
            {"tonemap-curve", "C", "aces | reinhard (with --tonemap)"},
            {"exposure", "X", "scale the linear colour before tone mapping (default 1)"},
            {"samples", "N", "MSAA samples 1, 2, 4, 8 (default 4)"},
            {"no-shadows", "", "the lights are not shadowed by the mesh (default: shadowed, in every lit mode)"},
            eval_option(),
            light_path_option()};
}

RendererOptions renderer_options(const Args& args)
{
    RendererOptions o;
    try {
        o.tm_evaluation = parse_tm_evaluation(args.get_or("eval", "auto"));
    } catch (const Error& e) {
        args.fail(std::string("--eval: ") + e.what());
    }
    try {
        o.light_path = parse_light_path_sampling(args.get_or("light-path", "auto"));
    } catch (const Error& e) {
        args.fail(std::string("--light-path: ") + e.what());
    }
    return o;
}

std::pair<uint32_t, uint32_t> parse_size(const Args& args, const std::string& fallback)
{
    return args.size("size", fallback, 16384);
}

glm::vec3 to_vec3(const std::array<double, 3>& a) { return glm::vec3(float(a[0]), float(a[1]), float(a[2])); }

Light parse_light(const Args& args, const std::string& spec)
{
    auto fail = [&] { args.fail("--light: expected dir:X,Y,Z:R,G,B or point:X,Y,Z:R,G,B, got '" + spec + "'"); };
    std::vector<std::string> parts;
    std::stringstream ss(spec);
    for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
    if (parts.size() != 3 || spec.back() == ':' || (parts[0] != "dir" && parts[0] != "point")) fail();
    glm::vec3 v[2];
    for (int k = 0; k < 2; ++k) {
        const auto t = Args::triple(parts[k + 1]);
        if (!t) fail();
        v[k] = to_vec3(*t);
        if (!std::isfinite(v[k].x) || !std::isfinite(v[k].y) || !std::isfinite(v[k].z)) fail();  // beyond float
    }
    if (parts[0] == "dir" && v[0] == glm::vec3(0.0f)) args.fail("--light " + spec + ": the direction is zero");
    return parts[0] == "dir" ? Light::directional(v[0], v[1]) : Light::point(v[0], v[1]);
}

Camera camera_from_args(const Args& args, const PreparedMesh& mesh, float aspect)
{
    const glm::vec3 centre = 0.5f * (mesh.bbox_min + mesh.bbox_max);
    const glm::vec3 target = args.vec3("target") ? to_vec3(*args.vec3("target")) : centre;
    const glm::vec3 up = args.vec3("up") ? to_vec3(*args.vec3("up")) : glm::vec3(0, 1, 0);
    const float fov = float(args.number("fov", 30.0, 1e-3, 179.0));
    const auto eye = args.vec3("eye");
    if (glm::length(up) == 0.0f) args.fail("--up: the up vector is zero");
    if (eye && !args.flag("frame")) {
        const glm::vec3 view = target - to_vec3(*eye);
        if (glm::length(view) == 0.0f) args.fail("--eye equals --target: no direction to look in");
        if (glm::length(glm::cross(view, up)) <= 1e-6f * glm::length(view) * glm::length(up))
            args.fail("--up is parallel to the view direction (--target - --eye)");
        return Camera{to_vec3(*eye), target, up, fov};
    }
    glm::vec3 direction = eye ? to_vec3(*eye) - target : glm::vec3(0, 0, 1);
    if (glm::length(direction) == 0.0f) args.fail("--frame: --eye equals --target, no direction to frame from");
    // Frame the bounds as seen from the direction, around --target when given.
    const glm::vec3 half = 0.5f * (mesh.bbox_max - mesh.bbox_min);
    Camera c = Camera::framing(target - half, target + half, aspect, direction, up, fov);
    return c;
}

std::vector<Light> preset_lights(const Args& args, const Camera& camera)
{
    const std::string preset = args.get_or("lights", "default");
    if (preset == "figure1") return figure1_lights(camera);
    if (preset == "back") return back_lights(camera);
    if (preset != "default") args.fail("--lights: '" + preset + "' is not one of default, figure1, back");
    return default_lights(camera);
}

std::vector<Light> lights_from_args(const Args& args, const Camera& camera)
{
    std::vector<Light> lights;
    for (const auto& spec : args.all("light")) lights.push_back(parse_light(args, spec));
    return lights.empty() ? preset_lights(args, camera) : lights;
}

// The mesh with its t_m per bake vertex: read from a baked file, or baked now (only for the
// modes that use it).
struct Scene {
    TriangleMesh mesh;
    PreparedMesh prepared;
    Material material;
    std::vector<glm::vec3> tm;     ///< per bake vertex when baked here, else empty
    std::vector<float> thickness;  ///< per bake vertex when baked here with transmission, else empty
    std::vector<glm::vec3> scattering_normal, normal_spread;  ///< per bake vertex when baked here, else empty
};

void set_scene(Renderer& renderer, const Scene& s)
{
    if (!s.mesh.baked_tm.empty())
        renderer.set_mesh(s.mesh, s.mesh.baked_tm, s.mesh.baked_thickness);  // per render vertex
    else
        renderer.set_mesh(s.prepared, s.tm, s.thickness, s.scattering_normal, s.normal_spread);
    renderer.set_material(s.material);
}

Scene load_scene(const Args& args, Context& ctx, const std::string& path, bool need_tm)
{
    Scene s;
    s.mesh = load_mesh_arg(path, read_options(args));
    s.prepared = prepare_mesh(s.mesh);
    s.material = material_from_args(args, s.prepared);
    if (!s.mesh.baked_tm.empty()) {
        // What the renderer refuses, named as the file has it (attribute and vertex).
        for (size_t i = 0; i < s.mesh.baked_tm.size(); ++i) {
            const glm::vec3 t = s.mesh.baked_tm[i];
            if (!(t.x >= 0.0f && t.y >= 0.0f && t.z >= 0.0f && std::isfinite(t.x + t.y + t.z)))
                throw Error(path + ": _TM of vertex " + std::to_string(i) + " is negative or not finite");
        }
        for (size_t i = 0; i < s.mesh.baked_thickness.size(); ++i)
            if (!(s.mesh.baked_thickness[i] >= 0.0f && std::isfinite(s.mesh.baked_thickness[i])))
                throw Error(path + ": _THICKNESS of vertex " + std::to_string(i) + " is negative or not finite");
        std::fprintf(stderr, "jade: t_m read from %s\n", s.mesh.name.c_str());
    } else if (need_tm && !s.material.opaque) {
        BakeSettings settings = bake_settings_from_args(args);
        std::fprintf(stderr, "jade: baking t_m of %s (%zu vertices, material %s) ...\n", s.mesh.name.c_str(),
                     s.prepared.vertex_count(), s.material.name.c_str());
        Baker baker(ctx);
        BakeResult r = baker.bake(s.prepared, s.material, settings);
        std::fprintf(stderr, "jade: baked in %s\n", format_ms(r.timings.wall_ms).c_str());
        s.tm = std::move(r.tm);
        s.thickness = std::move(r.thickness);
        s.scattering_normal = std::move(r.scattering_normal);
        s.normal_spread = std::move(r.normal_spread);
    }
    return s;
}

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
        settings.mode = parse_shading_mode(args.get_or("mode", "tm"));
    } catch (const Error& e) {
        args.fail(std::string("--mode: ") + e.what());
    }
    try {
        if (args.flag("tonemap")) settings.tone_map = parse_tone_map(args.get_or("tonemap-curve", "aces"));
    } catch (const Error& e) {
        args.fail(std::string("--tonemap-curve: ") + e.what());
    }
    settings.exposure = float(args.number("exposure", 1.0, 0.0, 1e6));
    settings.samples = args.count("samples", 4, 1, 8);
    settings.shadows = !args.flag("no-shadows");
    settings.separable_taps = args.count("taps", 17, 11, 25);
    settings.burley_samples = args.count("burley-samples", 40, 1, 80);
    if (settings.separable_taps != 11 && settings.separable_taps != 17 && settings.separable_taps != 25)
        args.fail("--taps: 11, 17 or 25");
    const std::string out = args.get_or("out", "render.png");
    check_output_file(args, "out", out, {".png", ".exr"});

    auto ctx = make_context(args);
    const bool need_tm = settings.mode == ShadingMode::Tm || settings.mode == ShadingMode::TmFalseColor;
    Scene scene = load_scene(args, *ctx, args.positional().empty() ? "bunny" : args.positional()[0], need_tm);
    Camera camera = camera_from_args(args, scene.prepared, float(settings.width) / float(settings.height));
    std::vector<Light> lights = lights_from_args(args, camera);

    Renderer renderer(*ctx, renderer_options(args));
    set_scene(renderer, scene);
    RenderedImage image = renderer.render(camera, lights, settings);
    save_image(out, int(image.width), int(image.height), image.rgba);
    std::printf("%s: %ux%u, %s, material %s, lights: %zu; GPU %s, wall %s\n", out.c_str(), image.width, image.height,
                std::string(shading_mode_name(settings.mode)).c_str(), scene.material.name.c_str(), lights.size(),
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
    Scene scene = load_scene(args, *ctx, args.get_or("mesh", "bunny"), true);
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
        std::printf("(%c) %-16s GPU %s\n", 'a' + k, std::string(shading_mode_name(modes[k])).c_str(),
                    format_ms(panel.gpu_ms).c_str());
    }
    save_image(out, int(figure.width), int(figure.height), figure.rgba);
    std::printf("%s: %ux%u, material %s\n", out.c_str(), figure.width, figure.height, scene.material.name.c_str());
    return 0;
}

namespace {
// CPU time of the whole process, all threads (lavapipe renders on this process's threads):
// the work done, whatever other jobs on the machine do to the wall time.
double process_cpu_ms()
{
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}
}  // namespace

int cmd_bench_render(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {
        {"repeat", "N", "frame pairs (lambert, tm) per size, alternating (default 30)"},
        {"samples", "N", "MSAA samples 1, 2, 4, 8 (default 4, as jade render)"},
        {"lights", "PRESET",
         "default (front key + fill) | figure1 (back light, front key, "
         "fill) | back (front key + back light): with a back light tm "
         "draws the transmission term too"},
        {"sizes", "N,N", "image sizes, N (square) or WxH (default 512,1024)"},
        {"mode", "M", "the mode timed against lambert (default tm; e.g. separable)"},
        {"taps", "N", "separable: taps of each 1-D blur pass, 11 | 17 | 25 (default 17)"},
        {"burley-samples", "N", "burley: samples per pixel, 1..80 (default 40)"},
        {"no-shadows", "", "both modes without shadows"},
        {"shadow-cost", "MODE", "instead of lambert against tm: MODE without shadows against MODE with them"},
        eval_option(),
        light_path_option()};
    const char* const usage =
        "usage: jade bench render [MESH] [options]\n\nFrame time of tm against lambert shading at 512x512 "
        "and 1024x1024, the same scene,\nmeasured alternately in one run (GPU timestamps, wall time, and the "
        "CPU time of the\nprocess, which is lavapipe's work when the machine is shared).";
    Args args("bench render", all_options({device_options(), material_options(), bake_options(), own}), argc, argv, 3);
    if (print_help(args, usage)) return 0;
    const uint32_t repeat = args.count("repeat", 30, 1, 10000);
    const uint32_t samples = args.count("samples", 4, 1, 8);
    std::vector<std::pair<uint32_t, uint32_t>> sizes;  // width, height
    {
        std::stringstream list(args.get_or("sizes", "512,1024"));
        for (std::string word; std::getline(list, word, ',');) {
            const size_t x = word.find('x');
            long n[2] = {0, 0};
            for (int k = 0; k < (x == std::string::npos ? 1 : 2); ++k) {
                const std::string part = k == 0 ? word.substr(0, x) : word.substr(x + 1);
                char* end = nullptr;
                n[k] = std::strtol(part.c_str(), &end, 10);
                if (part.empty() || *end != '\0' || n[k] < 1 || n[k] > 16384)
                    args.fail("--sizes: '" + word + "' is not N or WxH in 1..16384");
            }
            sizes.push_back({uint32_t(n[0]), uint32_t(x == std::string::npos ? n[0] : n[1])});
        }
    }
    // The two configurations timed against each other: (mode, shadows).
    std::pair<ShadingMode, bool> config[2] = {{ShadingMode::Lambert, !args.flag("no-shadows")},
                                              {ShadingMode::Tm, !args.flag("no-shadows")}};
    try {
        config[1].first = parse_shading_mode(args.get_or("mode", "tm"));
    } catch (const Error& e) {
        args.fail(std::string("--mode: ") + e.what());
    }
    if (const auto mode = args.get("shadow-cost")) {
        try {
            config[0] = {parse_shading_mode(*mode), false}, config[1] = {parse_shading_mode(*mode), true};
        } catch (const Error& e) {
            args.fail(std::string("--shadow-cost: ") + e.what());
        }
    }
    const std::string names[2] = {
        std::string(shading_mode_name(config[0].first)) + (config[0].second ? "" : "/noshadow"),
        std::string(shading_mode_name(config[1].first)) + (config[1].second ? "" : "/noshadow")};
    auto ctx = make_context(args);
    Scene scene = load_scene(args, *ctx, args.positional().empty() ? "bunny" : args.positional()[0], true);
    Camera camera = Camera::framing(scene.prepared.bbox_min, scene.prepared.bbox_max);
    const std::vector<Light> lights = preset_lights(args, camera);
    Renderer renderer(*ctx, renderer_options(args));
    set_scene(renderer, scene);
    const bool thickness = !scene.thickness.empty() || !scene.mesh.baked_thickness.empty();
    std::printf(
        "mesh %s: %zu vertices, %zu triangles; material %s (%s; transmission %s); tm evaluation %s, light path per %s; "
        "device %s\n",
        scene.mesh.name.c_str(), scene.prepared.vertex_count(), scene.prepared.triangle_count(),
        scene.material.name.c_str(), scene.material.grey() ? "grey: 1 channel" : "RGB: 3 channels",
        !scene.material.transmission.enabled() || !thickness ? "off" : "on where a light is behind",
        std::string(tm_evaluation_name(renderer.tm_evaluation())).c_str(),
        std::string(light_path_sampling_name(renderer.light_path())).c_str(), ctx->device_info().name.c_str());
    std::printf("same camera, %zu lights (%s), %ux MSAA, RGBA16F target, specular on in both modes; %u frame pairs "
                "per size after 2 warm-up pairs\n",
                lights.size(), args.get_or("lights", "default").c_str(), samples, repeat);
    std::printf("%-10s %-8s %12s %12s %12s %12s\n", "size", "mode", "GPU median", "GPU min", "wall median", "wall min");
    // The machine may be shared: each iteration renders both modes back to back (in
    // alternating order, so neither always runs second) and the ratio is taken per pair, so
    // load that changes more slowly than one pair cancels. Quartiles of the pair ratios say how
    // noisy the run was.
    auto quantile = [](std::vector<double> v, double q) {
        std::sort(v.begin(), v.end());
        return v[size_t(std::lround(q * double(v.size() - 1)))];
    };
    const uint32_t taps = args.count("taps", 17, 11, 25);
    if (taps != 11 && taps != 17 && taps != 25) args.fail("--taps: 11, 17 or 25");
    for (const auto& [width, height] : sizes) {
        RenderSettings s;
        s.width = width, s.height = height, s.separable_taps = taps;
        s.burley_samples = args.count("burley-samples", 40, 1, 80);
        s.samples = samples;
        std::vector<double> gpu[2], wall[2], cpu[2], gpu_ratio, wall_ratio, cpu_ratio;
        for (int warm = 0; warm < 2; ++warm)  // pipelines, targets, caches
            for (const auto& [m, shadows] : config) s.mode = m, s.shadows = shadows, renderer.render(camera, lights, s);
        for (uint32_t i = 0; i < repeat; ++i) {
            for (int n = 0; n < 2; ++n) {
                const int k = (i % 2 == 0) ? n : 1 - n;
                s.mode = config[k].first, s.shadows = config[k].second;
                const double cpu0 = process_cpu_ms();
                RenderedImage img = renderer.render(camera, lights, s);
                cpu[k].push_back(process_cpu_ms() - cpu0);
                gpu[k].push_back(img.gpu_ms);
                wall[k].push_back(img.wall_ms);
            }
            gpu_ratio.push_back(gpu[1].back() / gpu[0].back());
            wall_ratio.push_back(wall[1].back() / wall[0].back());
            cpu_ratio.push_back(cpu[1].back() / cpu[0].back());
        }
        for (int k = 0; k < 2; ++k)
            std::printf("%4ux%-5u %-8s %12s %12s %12s %12s\n", width, height, names[k].c_str(),
                        format_ms(quantile(gpu[k], 0.5)).c_str(), format_ms(quantile(gpu[k], 0.0)).c_str(),
                        format_ms(quantile(wall[k], 0.5)).c_str(), format_ms(quantile(wall[k], 0.0)).c_str());
        std::printf("%4ux%-5u %s / %s: GPU %.3fx (median of %u pairs; quartiles %.3f-%.3f; ratio of mins %.3fx), "
                    "wall %.3fx (quartiles %.3f-%.3f)\n",
                    width, height, names[1].c_str(), names[0].c_str(), quantile(gpu_ratio, 0.5), repeat,
                    quantile(gpu_ratio, 0.25), quantile(gpu_ratio, 0.75), quantile(gpu[1], 0.0) / quantile(gpu[0], 0.0),
                    quantile(wall_ratio, 0.5), quantile(wall_ratio, 0.25), quantile(wall_ratio, 0.75));
        std::printf("%4ux%-5u %s / %s: CPU time of this process (lavapipe's threads) %.3fx (quartiles %.3f-%.3f; "
                    "%s %s, %s %s median)\n",
                    width, height, names[1].c_str(), names[0].c_str(), quantile(cpu_ratio, 0.5), quantile(cpu_ratio, 0.25),
                    quantile(cpu_ratio, 0.75), names[0].c_str(), format_ms(quantile(cpu[0], 0.5)).c_str(),
                    names[1].c_str(), format_ms(quantile(cpu[1], 0.5)).c_str());
    }
    return 0;
}

}  // namespace jade::cli
