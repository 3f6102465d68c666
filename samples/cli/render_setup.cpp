// render_setup.cpp - what `jade render`, `jade figure1` and `jade bench render` share: their
// options, the renderer's options, the camera and lights from the command line, and the mesh
// with its bake (read from a baked file or baked now).
#include "render_setup.hpp"

#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/bake.hpp>
#include <jade/io.hpp>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <optional>

namespace jade::cli {

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
    return {{"mode", "M", "lambert | curvature | tm | tm-false-color | filament | separable | burley (default tm)"},
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
            {"filament-thickness", "X",
             "filament: Filament's thickness as a constant in [0, 1] (default: the baked one, normalised)"},
            eval_option(),
            light_path_option()};
}

RendererOptions renderer_options(const Args& args)
{
    dev::RendererStudy study;
    try {
        study.tm_evaluation = parse_tm_evaluation(args.get_or("eval", "auto"));
    } catch (const Error& e) {
        args.fail(std::string("--eval: ") + e.what());
    }
    try {
        study.light_path = dev::parse_light_path_sampling(args.get_or("light-path", "auto"));
    } catch (const Error& e) {
        args.fail(std::string("--light-path: ") + e.what());
    }
    RendererOptions o;
    dev::set_study(o, study);
    return o;
}

std::pair<uint32_t, uint32_t> parse_size(const Args& args, const std::string& fallback)
{
    return args.size("size", fallback, 16384);
}

namespace {
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
}  // namespace

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

void set_scene(Renderer& renderer, const MeshScene& s)
{
    if (!s.mesh.baked_tm.empty())
        renderer.set_mesh(s.mesh, s.mesh.baked_tm, s.mesh.baked_thickness, s.mesh.baked_scattering_normal,
                          s.mesh.baked_normal_spread);  // per render vertex
    else
        renderer.set_mesh(s.prepared, s.tm, s.thickness, s.scattering_normal, s.normal_spread);
    renderer.set_material(s.material);
}

MeshScene load_scene(const Args& args, Context& ctx, const std::string& path, bool need_tm)
{
    MeshScene s;
    ReadOptions options = read_options(args);
    std::optional<Material> baked_material;  // what a file written by jade bake was baked with
    options.baked_material = &baked_material;
    s.mesh = load_mesh_arg(path, options);
    s.prepared = prepare_mesh(s.mesh);
    s.material = material_from_args(args, s.prepared, baked_material);
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
        for (size_t i = 0; i < s.mesh.baked_scattering_normal.size(); ++i) {
            const float length = glm::length(s.mesh.baked_scattering_normal[i]);
            if (!(length > 0.0f && std::isfinite(length)))
                throw Error(path + ": _SCATTERING_NORMAL of vertex " + std::to_string(i) + " is zero or not finite");
        }
        for (size_t i = 0; i < s.mesh.baked_normal_spread.size(); ++i) {
            const glm::vec3 v = s.mesh.baked_normal_spread[i];
            if (!(v.x >= 0.0f && v.x <= 1.0f && v.y >= 0.0f && v.y <= 1.0f && v.z >= 0.0f && v.z <= 1.0f))
                throw Error(path + ": _NORMAL_SPREAD of vertex " + std::to_string(i) + " is not in [0, 1]");
        }
        if (baked_material)
            std::fprintf(stderr,
                         "jade: %s was baked with material %s (JADE_materials_translucency; --material, --medium or "
                         "--mm-per-unit replace it)\n",
                         s.mesh.name.c_str(), baked_material->name.c_str());
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

}  // namespace jade::cli
