// jade plan SCENE | jade scene SCENE: a glTF scene analysed into a plan (objects, passes, shader
// variants, buffers and GPU memory, what the bake cache already holds), and rendered with only
// the planned passes (--verbose lists the passes that ran).
#include "commands.hpp"

#include <jade/dev/cache.hpp>
#include <jade/dev/context.hpp>
#include <jade/dev/names.hpp>
#include <jade/io.hpp>
#include <jade/dev/scene.hpp>
#include <jade/scene.hpp>

#include <cstdio>
#include <optional>

namespace jade::cli {

std::vector<OptionSpec> scene_options()
{
    return {{"cache", "DIR", "bake cache folder: static bakes are read from it or stored in it"},
            {"mode", "M", "translucent objects: tm | tm-false-color (default tm); opaque ones are lambert"}};
}

SceneSettings scene_settings_from_args(const Args& args)
{
    SceneSettings s;
    s.bake = bake_settings_from_args(args);
    try {
        s.mode = dev::parse_shading_mode(args.get_or("mode", "tm"));
    } catch (const Error& e) {
        args.fail(std::string("--mode: ") + e.what());
    }
    if (s.mode != ShadingMode::Tm && s.mode != ShadingMode::TmFalseColor)
        args.fail("--mode: a scene is drawn with tm or tm-false-color");
    return s;
}

Scene load_scene_arg(const Args& args)
{
    if (args.positional().empty()) args.fail("no scene file (a .gltf or .glb)");
    std::vector<std::string> warnings;
    Scene scene = load_scene(args.positional()[0], &warnings, read_options(args));
    for (const auto& w : warnings) std::fprintf(stderr, "jade: warning: %s\n", w.c_str());
    return scene;
}

std::optional<dev::BakeCache> cache_from_args(const Args& args)
{
    if (auto dir = args.get("cache")) return dev::BakeCache(*dir);
    return std::nullopt;
}

Camera scene_camera(glm::vec3 lo, glm::vec3 hi, float aspect)
{
    return Camera::framing(lo, hi, aspect, glm::vec3(0.35f, 0.45f, 1.0f));
}

int cmd_plan(int argc, char** argv)
{
    Args args("plan", all_options({scene_options(), bake_options()}), argc, argv, 2);
    if (print_help(args,
                   "usage: jade plan SCENE.gltf [--cache DIR] [options]\n\nThe passes each object of the scene "
                   "needs, their shader variants, buffers and\nestimated GPU memory, and whether the cache holds each "
                   "static bake. No GPU is used."))
        return 0;
    const Scene scene = load_scene_arg(args);
    const SceneSettings settings = scene_settings_from_args(args);
    const auto cache = cache_from_args(args);
    const ScenePlan plan = plan_scene(scene, settings, cache ? dev::cached_bakes(*cache) : StaticBakeSource{});
    std::printf("scene %s%s\n%s", scene.name.c_str(),
                cache ? (", cache " + cache->folder().string()).c_str()
                      : " (no --cache: static objects bake every run)",
                plan.describe().c_str());
    return 0;
}

int cmd_scene(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {{"out", "FILE", "output .png or .exr (default scene.png)"},
                                         {"size", "N", "square image size in pixels (default 512)"},
                                         {"time", "T", "seconds: the deformers' time (default 0.5)"},
                                         {"samples", "N", "MSAA samples 1, 2, 4, 8 (default 4)"},
                                         {"max-memory", "MIB",
                                          "refuse a scene whose plan needs more than this (default 8192; the "
                                          "host keeps the objects' meshes as well)"}};
    Args args("scene", all_options({scene_options(), device_options(), bake_options(), input_options(), own}), argc,
              argv, 2);
    if (print_help(args,
                   "usage: jade scene SCENE.gltf [--cache DIR] [--out F.png] [--verbose] [options]\n\nRenders a glTF "
                   "scene running only the planned passes (see jade plan); --verbose\nlists the passes that ran."))
        return 0;
    const std::filesystem::path out = args.get_or("out", "scene.png");
    check_output_file(args, "out", out, {".png", ".exr"});
    const Scene scene = load_scene_arg(args);
    const SceneSettings settings = scene_settings_from_args(args);
    const auto cache = cache_from_args(args);
    RenderSettings rs;
    rs.width = rs.height = args.count("size", 512, 1, 16384);
    rs.samples = args.count("samples", 4, 1, 8);
    rs.tone_map = ToneMap::AcesFitted;
    const double t = args.number("time", 0.5, -1e6, 1e6);
    const double budget_mib = args.number("max-memory", 8192.0, 1.0, 1e9);
    auto ctx = make_context(args);
    // Checked against the plan before anything of the scene is allocated: a scene that instances
    // a deforming mesh 100,000 times would otherwise run the machine out of memory.
    const StaticBakeSource source = cache ? dev::cached_bakes(*cache) : StaticBakeSource{};
    const ScenePlan plan = plan_scene(scene, settings, source);
    const uint64_t need = plan.resident_bytes() + plan.transient_peak_bytes();
    const uint64_t heap = dev::device_info(*ctx).device_local_heap_bytes;
    auto mib = [](double bytes) {
        char b[48];
        if (bytes >= double(1ull << 30))
            std::snprintf(b, sizeof b, "%.1f GiB", bytes / double(1ull << 30));
        else
            std::snprintf(b, sizeof b, "%.1f MiB", bytes / double(1u << 20));
        return std::string(b);
    };
    if (heap > 0 && need > heap)
        throw Error(args.positional()[0] + ": the scene's plan needs " + mib(double(need)) + " (" +
                    mib(double(plan.resident_bytes())) + " while drawing, " + mib(double(plan.transient_peak_bytes())) +
                    " at the largest once-only pass; see jade plan) but " + "the device's largest memory heap holds " +
                    mib(double(heap)));
    if (double(need) > budget_mib * double(1u << 20))
        throw Error(args.positional()[0] + ": the scene's plan needs " + mib(double(need)) +
                    " (see jade plan), over --max-memory " + mib(budget_mib * double(1u << 20)));
    SceneRenderer renderer(*ctx, scene, settings, source);
    const Camera camera = scene_camera(renderer.bbox_min(), renderer.bbox_max(), 1.0f);
    const auto lights = default_lights(camera);
    RenderedImage img = renderer.render(t, camera, lights, rs);
    save_image(out, int(img.width), int(img.height), img.rgba);
    // A cache entry that was there but could not be used (stale, corrupt) is said even without
    // --verbose: the next run will read the entry just stored.
    for (const dev::PassRecord& p : dev::passes_run(renderer))
        if (cache && p.kind == dev::PassKind::StaticBake && !p.note.empty() && p.note != "missing")
            std::fprintf(stderr, "jade scene: %s: cache entry not used (%s); baked again and stored\n",
                         p.object.c_str(), p.note.c_str());
    if (args.flag("verbose")) {
        std::printf("passes run:\n");
        for (const dev::PassRecord& p : dev::passes_run(renderer))
            std::printf("  %-24s %-13s %10s  %s\n", p.object.c_str(), std::string(dev::pass_kind_name(p.kind)).c_str(),
                        p.wall_ms > 0 ? format_ms(p.wall_ms).c_str() : "", p.note.c_str());
        const ObjectCounts c = dev::created_objects(*ctx);
        std::printf("GPU objects created: %llu compute pipelines, %llu graphics pipelines, %llu buffers (%.2f MiB "
                    "device-local), "
                    "%llu images\n",
                    (unsigned long long)c.compute_pipelines, (unsigned long long)c.graphics_pipelines,
                    (unsigned long long)c.buffers, double(c.device_buffer_bytes) / double(1u << 20),
                    (unsigned long long)c.images);
    }
    std::printf("wrote %s (%ux%u, draw %s GPU)\n", out.string().c_str(), img.width, img.height,
                format_ms(img.gpu_ms).c_str());
    return 0;
}

}  // namespace jade::cli
