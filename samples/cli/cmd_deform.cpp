// jade deform: the deformable-mesh demo. Per frame: deform the bake vertices on the GPU
// (procedural bend/twist/squash/wave, or a glTF skin + morph targets + animation), recompute
// normals and areas on the GPU, re-bake AO and t_m, render the `tm` shading; writes the frames
// as PNG and an animated GIF and prints the GPU time of each stage per frame.
//
// GPU-resident: jade::DynamicBake refits both trees on the GPU every frame and reads the
// deformer's buffers; Renderer::update_vertices copies the deformed positions, normals and the
// new t_m into the renderer's vertex buffer on the GPU. No mesh data goes through the host per
// frame (only the finished image is read back). Each stage is its own submission here so that
// its GPU time can be printed; a real-time host records MeshDeformer::record,
// DynamicBake::record, Renderer::record_vertex_update and Renderer::record into one command buffer.
#include "commands.hpp"

#include <jade/dev/clock.hpp>
#include <jade/deform.hpp>
#include <jade/dev/deform.hpp>
#include <jade/dev/names.hpp>
#include <jade/io.hpp>
#include <jade/render.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

namespace jade::cli {
namespace {

std::vector<OptionSpec> deform_options()
{
    return {{"deformer", "D",
             "bend | twist | squash | wave | gltf (default bend; gltf needs a .gltf/.glb MESH with an "
             "animation)"},
            {"frames", "N", "frames over one cycle (default 8)"},
            {"out", "DIR", "output folder for frame_NNN.png and deform.gif (default deform_out)"},
            {"anim", "FILE", "animated image in --out (default deform.gif)"},
            {"axis", "A", "x | y | z: the axis the procedural deformers act along (default y)"},
            {"amplitude", "X",
             "bend/twist: angle at the top (rad); squash: stretch (0..1); wave: fraction of the "
             "length (defaults 0.8, 1.2, 0.25, 0.04)"},
            {"wavelength", "F", "wave: wavelength as a fraction of the length (default 0.5)"},
            {"period", "S", "seconds per cycle (procedural, default 2; gltf: the animation's duration)"},
            {"animation", "K", "gltf: index of the animation to play (default 0)"},
            {"size", "WxH", "frame size in pixels (default 256x256)"},
            {"lights", "PRESET", "figure1 (back light: thin parts glow, default) | default"},
            {"amortise", "N",
             "re-trace 1/N of the AO rays and re-evaluate 1/N of the t_m values per frame (N divides the "
             "ray count; default 1: everything every frame)"}};
}

struct StageTimes {
    double deform = 0, normals = 0, ao = 0, tm = 0, draw = 0, wall = 0;
};

void print_row(const char* label, const StageTimes& t)
{
    std::printf("%-7s %9.2f %9.2f %10.1f %10.1f %9.2f %10.1f\n", label, t.deform, t.normals, t.ao, t.tm, t.draw,
                t.wall);
}

}  // namespace

int cmd_deform(int argc, char** argv)
{
    // Draft quality unless --quality is given: the demo re-bakes every frame.
    std::vector<std::string> words(argv, argv + argc);
    bool has_quality = false;
    for (const auto& w : words) has_quality = has_quality || w == "--quality" || w.rfind("--quality=", 0) == 0;
    if (!has_quality) words.insert(words.end(), {"--quality", "draft"});
    std::vector<char*> word_ptrs;
    for (auto& w : words) word_ptrs.push_back(w.data());
    const char* const usage =
        "usage: jade deform [MESH] --deformer bend|twist|squash|wave|gltf [options]\n\nDeforms the mesh "
        "on the GPU frame by frame, re-bakes AO and t_m and renders t_m shading;\nwrites DIR/frame_NNN.png, "
        "an animated GIF and a per-stage GPU time table (ms).\n(--quality defaults to draft here.)";
    Args args("deform",
              all_options({device_options(), material_options(), bake_options(), input_options(), deform_options()}),
              int(word_ptrs.size()), word_ptrs.data(), 2);
    if (print_help(args, usage)) return 0;
    if (args.positional().size() > 1) args.fail("expects at most one MESH");
    const std::string mesh_path = args.positional().empty() ? "bunny" : args.positional()[0];
    const std::string kind_name = args.get_or("deformer", "bend");
    const bool gltf = kind_name == "gltf";
    std::optional<DeformerKind> kind;
    if (!gltf) {
        try {
            kind = dev::parse_deformer(kind_name);
        } catch (const Error& e) {
            args.fail(std::string("--deformer: ") + e.what() + " or gltf");
        }
    }
    const uint32_t frames = args.count("frames", 8, 1, 10000);
    const std::filesystem::path out_dir = args.get_or("out", "deform_out");
    const std::string anim_name = args.get_or("anim", "deform.gif");
    const auto [width, height] = args.size("size", "256x256", 8192);
    const std::string axis_name = args.get_or("axis", "y");
    if (axis_name != "x" && axis_name != "y" && axis_name != "z")
        args.fail("--axis: '" + axis_name + "' is not x, y or z");
    const uint32_t axis = uint32_t(axis_name[0] - 'x');
    const std::string light_preset = args.get_or("lights", "figure1");
    if (light_preset != "figure1" && light_preset != "default")
        args.fail("--lights: '" + light_preset + "' is not figure1 or default");

    // The rest mesh and what moves it.
    std::optional<AnimatedMesh> animated;
    TriangleMesh mesh;
    if (gltf) {
        animated = load_animated_gltf(mesh_path, read_options(args));
        mesh = animated->mesh;
    } else {
        mesh = load_mesh_arg(mesh_path, read_options(args));
    }
    const PreparedMesh rest = prepare_mesh(mesh);
    const size_t animation = args.count("animation", 0, 0, 1000000);
    double cycle = args.number("period", 2.0, 1e-6, 1e6);
    ProceduralDeformer procedural;
    if (gltf) {
        if (animated->animations.empty()) args.fail("--deformer gltf: " + mesh.name + " has no animation");
        if (animation >= animated->animations.size())
            args.fail("--animation: " + std::to_string(animation) + " is out of range (" + mesh.name + " has " +
                      std::to_string(animated->animations.size()) + ")");
        if (!args.get("period")) cycle = animated->animations[animation].duration();
        if (!(cycle > 0.0)) cycle = 1.0;
    } else {
        procedural = ProceduralDeformer::fit(*kind, rest, axis);
        procedural.period = float(cycle);
        if (args.get("amplitude")) {
            const double a = args.number("amplitude", 0.0, -1e3, 1e3);
            procedural.amplitude = float(*kind == DeformerKind::Wave ? a * procedural.length : a);
        }
        procedural.wavelength = float(args.number("wavelength", 0.5, 1e-6, 1e6) * procedural.length);
        try {
            dev::validate_deformer(procedural);
        } catch (const Error& e) {
            args.fail(std::string("--amplitude/--wavelength/--period: ") + e.what());
        }
    }
    const Material material = material_from_args(args, rest);  // sized by the rest mesh: fixed over frames
    const BakeSettings bake_settings = bake_settings_from_args(args);

    auto ctx = make_context(args);
    MeshDeformer deformer(*ctx, rest);
    if (gltf) deformer.set_skin(bind_skin(*animated, rest));
    auto time_of = [&](uint32_t f) { return cycle * double(f) / double(frames); };
    auto deform_frame = [&](uint32_t f) {
        return gltf ? deformer.deform(evaluate_pose(*animated, animation, time_of(f)))
                    : deformer.deform(procedural, time_of(f));
    };

    // One fixed camera for the whole sequence, framing the union of every frame's bounds (the
    // deform passes are cheap; this runs them once before the timed loop).
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (uint32_t f = 0; f < frames; ++f) {
        deform_frame(f);
        for (const auto& p : deformer.read().positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    Camera camera = Camera::framing(lo, hi, float(width) / float(height));
    {  // planes around every frame's bounds (set_mesh only sees the rest pose)
        const float radius = 0.5f * glm::length(hi - lo), distance = glm::length(camera.eye - 0.5f * (lo + hi));
        camera.near_plane = std::max(distance - 1.05f * radius, 1e-3f * radius);
        camera.far_plane = distance + 1.05f * radius;
    }
    const std::vector<Light> lights = light_preset == "figure1" ? figure1_lights(camera) : default_lights(camera);
    RenderSettings render_settings;
    render_settings.width = width, render_settings.height = height;
    render_settings.mode = ShadingMode::Tm;
    render_settings.tone_map = ToneMap::AcesFitted;

    check_output_folder("out", out_dir);
    Baker baker(*ctx);
    DynamicBake rebake(baker, rest, material, bake_settings);
    if (const uint32_t n = args.count("amortise", 1, 1, 64); n > 1) {
        try {
            rebake.set_amortisation({n, n});
        } catch (const Error& e) {
            args.fail(std::string("--amortise: ") + e.what());
        }
    }
    Renderer renderer(*ctx);
    renderer.set_material(material);
    renderer.set_mesh(rest);  // the triangles and curvature; vertices follow on the GPU each frame
    std::printf("jade deform: %s, %zu bake vertices, %s, %u frames over %.3g s, bake %u AO rays, theta %.2g, %ux%u\n",
                mesh.name.c_str(), rest.vertex_count(),
                gltf ? ("glTF animation '" + animated->animations[animation].name + "'").c_str() : kind_name.c_str(),
                frames, cycle, bake_settings.ao.rays, bake_settings.tm_opening_ratio, width, height);
    std::printf("GPU time per stage (ms; bake t_m includes the GPU BVH and cluster-tree refits); wall: the whole frame "
                "on the host\n");
    std::printf("%-7s %9s %9s %10s %10s %9s %10s\n", "frame", "deform", "normals", "bake AO", "bake t_m", "draw",
                "wall");
    std::vector<std::vector<float>> images;
    StageTimes sum;
    for (uint32_t f = 0; f < frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        StageTimes st;
        const DeformTimings dt = deform_frame(f);
        st.deform = dt.deform_ms, st.normals = dt.normals_ms;
        const MeshDeformer::Buffers d = deformer.buffers();
        const BakeResult baked = rebake.bake(d.positions, d.normals, d.areas, /*read_back=*/false);
        for (const auto& [stage, ms] : baked.timings.gpu_stages) (stage == "ao" ? st.ao : st.tm) += ms;
        renderer.update_vertices(d.positions, d.normals, rebake.buffers().tm, rebake.buffers().thickness,
                                 rebake.buffers().scattering_normal);
        RenderedImage image = renderer.render(camera, lights, render_settings);
        st.draw = image.gpu_ms;
        char name[32];
        std::snprintf(name, sizeof name, "frame_%03u.png", f);
        save_image(out_dir / name, int(image.width), int(image.height), image.rgba);
        images.push_back(std::move(image.rgba));
        st.wall = ms_since(t0);
        print_row(std::to_string(f).c_str(), st);
        std::fflush(stdout);
        sum.deform += st.deform, sum.normals += st.normals, sum.ao += st.ao, sum.tm += st.tm, sum.draw += st.draw,
            sum.wall += st.wall;
    }
    const double n = double(frames);
    print_row("average", {sum.deform / n, sum.normals / n, sum.ao / n, sum.tm / n, sum.draw / n, sum.wall / n});
    const auto anim_path = out_dir / anim_name;
    save_animation(anim_path, int(width), int(height), images, std::min(100.0, std::max(0.01, n / cycle)));
    std::printf("%s: %u frames; %s/frame_000.png ... frame_%03u.png\n", anim_path.string().c_str(), frames,
                out_dir.string().c_str(), frames - 1);
    return 0;
}

}  // namespace jade::cli
