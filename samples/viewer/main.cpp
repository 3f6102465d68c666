// jade-view - the interactive viewer (also `jade view ...`, which executes this binary).
//
//   jade-view [MESH] [options]     MESH: a mesh file, "bunny" (default) or "sphere"
//
// A GLFW window with a Vulkan swapchain; Jade adopts the viewer's device and records its draw
// into the viewer's command buffer; a Dear ImGui panel edits camera, lights, material, shading,
// bake quality and deformation and shows frame and stage times. docs/viewer.md has the design.
// Exit status: 0 done; 1 an error; 2 bad arguments or the validation layer reported anything.
#include "app.hpp"

#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/material.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

namespace {

const char* kUsage = "usage: jade-view [MESH] [options]      (also: jade view [MESH] [options])\n"
                     "  MESH                 mesh file (.off .ply .obj .gltf .glb), 'bunny' (default) or 'sphere'\n"
                     "  --size WxH           window size in pixels (default 800x600)\n"
                     "  --frames N           render N frames, then exit (default: until the window is closed)\n"
                     "  --screenshot FILE    write the last presented frame (.png sRGB 8 bit, .exr) - needs --frames\n"
                     "  --no-ui              hide the ImGui panel\n"
                     "  --mode M             lambert | curvature | tm | tm-false-color | filament (default tm)\n"
                     "  --material NAME      a preset of jade::material_preset_names() (default jade)\n"
                     "  --strength X         shading strength, rad^2 per unit t_m (default: the preset's)\n"
                     "  --quality Q          bake quality draft | default | high (default default)\n"
                     "  --deform KIND        none | bend | twist | squash | wave (default none)\n"
                     "  --time T             deformation time in seconds (with --no-animate: fixed)\n"
                     "  --no-animate         do not advance the deformation time\n"
                     "  --lights L           default | figure1 (default default)\n"
                     "  --samples N          MSAA samples 1, 2, 4, 8 (default 4)\n"
                     "  --no-vsync           present without waiting for vertical blank when possible\n"
                     "  --validation         Khronos validation layer (also JADE_VALIDATION=1); any message: exit 2\n"
                     "Controls: drag with the left mouse button to orbit, wheel to zoom, the panel for the rest.\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

double number(const std::string& flag, const char* text, double lo, double hi)
{
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (!*text || *end || !(v >= lo && v <= hi))
        throw UsageError(flag + ": expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                         "], got '" + text + "'");
    return v;
}

template <class List> int index_of(const std::string& flag, const std::string& value, const List& names)
{
    const auto it = std::find(names.begin(), names.end(), value);
    if (it == names.end()) {
        std::string all;
        for (const auto& n : names) all += (all.empty() ? "" : ", ") + std::string(n);
        throw UsageError(flag + ": '" + value + "' is not one of " + all);
    }
    return int(it - names.begin());
}

samples::viewer::Options parse(int argc, char** argv)
{
    samples::viewer::Options o;
    if (const char* v = std::getenv("JADE_VALIDATION"); v && *v && std::strcmp(v, "0") != 0) o.validation = true;
    bool mesh_given = false, strength_given = false, material_given = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) throw UsageError(a + ": missing value");
            return argv[++i];
        };
        if (a == "--size") {
            const std::string s = value();
            unsigned w = 0, h = 0;
            char x = 0, extra = 0;
            if (std::sscanf(s.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || x != 'x' || w == 0 || h == 0 ||
                w > 16384 || h > 16384)
                throw UsageError("--size: expected WxH with 1..16384 pixels each, got '" + s + "'");
            o.width = w;
            o.height = h;
        } else if (a == "--frames")
            o.frames = uint32_t(number(a, value(), 1, 1e9));
        else if (a == "--screenshot")
            o.screenshot = value();
        else if (a == "--no-ui")
            o.ui = false;
        else if (a == "--mode")
            o.state.mode = jade::ShadingMode(index_of(
                a, value(), std::vector<std::string>{"lambert", "curvature", "tm", "tm-false-color", "filament"}));
        else if (a == "--material") {
            o.state.material = index_of(a, value(), jade::material_preset_names());
            material_given = true;
        } else if (a == "--strength") {
            o.state.strength = float(number(a, value(), 0, 1e6));
            strength_given = true;
        } else if (a == "--quality")
            o.state.quality = jade::Quality(index_of(a, value(), std::vector<std::string>{"draft", "default", "high"}));
        else if (a == "--deform")
            o.state.deformation = index_of(a, value(), samples::viewer::deformation_names());
        else if (a == "--time")
            o.state.time = number(a, value(), 0, 1e6);
        else if (a == "--no-animate")
            o.state.animate = false;
        else if (a == "--lights")
            o.state.figure1_lights = index_of(a, value(), std::vector<std::string>{"default", "figure1"}) == 1;
        else if (a == "--samples") {
            o.samples = uint32_t(number(a, value(), 1, 8));
            if (o.samples & (o.samples - 1)) throw UsageError("--samples: expected 1, 2, 4 or 8");
        } else if (a == "--no-vsync")
            o.vsync = false;
        else if (a == "--validation")
            o.validation = true;
        else if (!a.empty() && a[0] != '-' && !mesh_given) {
            o.mesh = a;
            mesh_given = true;
        } else
            throw UsageError("unknown argument '" + a + "'");
    }
    if (!o.screenshot.empty() && o.frames == 0)
        throw UsageError("--screenshot needs --frames N (the frame it captures is the last)");
    if (mesh_given && !material_given) {
        // A file written by `jade bake` names its material (JADE_materials_translucency): drawn
        // with it, as `jade render` does, when it is one of the presets the panel offers.
        std::optional<jade::Material> baked;
        jade::ReadOptions read;
        read.baked_material = &baked;
        try {
            (void)jade::load_mesh(o.mesh, read);
        } catch (const jade::Error&) {
            // The scene's own load reports it.
        }
        const auto& names = jade::material_preset_names();
        if (baked) {
            const auto it = std::find(names.begin(), names.end(), baked->name);
            if (it != names.end())
                o.state.material = int(it - names.begin());
            else
                std::fprintf(stderr, "jade view: %s was baked with material '%s', not a preset; drawn with '%s'\n",
                             o.mesh.c_str(), baked->name.c_str(), std::string(names.at(0)).c_str());
        }
    }
    if (o.state.material < 0) o.state.material = 0;
    if (!strength_given) {
        // The preset's own strength (what `jade render` uses without --strength).
        o.state.strength =
            jade::material_preset(jade::material_preset_names().at(size_t(o.state.material)), 1.0).strength;
    }
    return o;
}

}  // namespace

int main(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
            std::fputs(kUsage, stdout);
            return 0;
        }
    samples::viewer::Options options;
    try {
        options = parse(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "jade-view: %s\n%s", e.what(), kUsage);
        return 2;
    }
    try {
        return samples::viewer::run(options);
    } catch (const std::exception& e) {  // jade::Error and the viewer's own failures
        std::fprintf(stderr, "jade-view: error: %s\n", e.what());
        return 1;
    }
}
