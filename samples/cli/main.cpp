// jade - the command-line sample: inspect devices and meshes, bake, render, benchmark.
#include "commands.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

const char* kUsage =
    "jade - real-time translucency from the translucency magnitude (Kubo et al. 2015), on Vulkan\n"
    "\n"
    "usage: jade COMMAND [ARGS] [--help]\n"
    "\n"
    "commands:\n"
    "  info [MESH]        the Vulkan device (or a mesh after preparation)\n"
    "  bake MESH --out F  AO and t_m on the GPU, written as glTF with _AO and _TM attributes\n"
    "  bench bake MESH    GPU bake timings against the float64 CPU reference and the all-pairs pass\n"
    "  render MESH        image with t_m shading (or lambert, curvature, false colour) as PNG/EXR\n"
    "  figure1            the poster's Figure 1: the blue-jewel bunny in four shading modes\n"
    "  bench render MESH  frame time of t_m shading against Lambert at 512^2 and 1024^2\n"
    "  report [MESH...]   error of every approximation against GPU and wall time (--out DIR)\n"
    "  fidelity           the shading modes against the committed path-traced references (LDR FLIP)\n"
    "  deform [MESH]      deforming mesh demo: GPU deform, re-bake, t_m frames and a GIF\n"
    "  bench deform       frames per second of the per-frame re-bake, full and amortised, with errors\n"
    "  plan SCENE.gltf    the passes, shader variants and GPU memory a glTF scene needs (--cache DIR)\n"
    "  scene SCENE.gltf   render a glTF scene running only the planned passes (--verbose lists them)\n"
    "  bench render --scene SCENE.gltf  cached static scene against the same scene never baked\n"
    "  view [MESH]        interactive viewer window (runs jade-view, built with JADE_WITH_GLFW=ON)\n"
    "\n"
    "Environment: JADE_DEVICE (device name), JADE_VALIDATION=1 (Khronos validation layer).\n";

// `jade bench render --scene FILE` is the scene benchmark (cmd_bench.cpp); without --scene,
// the single-mesh one (cmd_render.cpp).
bool has_scene_flag(int argc, char** argv)
{
    for (int i = 3; i < argc; ++i)
        if (!std::strcmp(argv[i], "--scene") || !std::strncmp(argv[i], "--scene=", 8)) return true;
    return false;
}

// `jade view ...` executes the sibling binary jade-view with the same arguments, so that this
// CLI never links GLFW or ImGui (and runs on machines without a display).
int exec_viewer(int argc, char** argv)
{
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    std::string dir = ".";
    if (n > 0) {
        self[n] = 0;
        dir = self;
        dir = dir.substr(0, dir.find_last_of('/'));
    }
    const std::string viewer = dir + "/jade-view";
    std::vector<char*> args{const_cast<char*>(viewer.c_str())};
    for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    execv(viewer.c_str(), args.data());
    std::fprintf(stderr,
                 "jade view: cannot run %s: %s\n(the viewer is built when GLFW and Dear ImGui are found, or with "
                 "-DJADE_WITH_GLFW=ON; Debian packages libglfw3-dev libimgui-dev)\n",
                 viewer.c_str(), std::strerror(errno));
    return 1;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    std::string command = argv[1];
    try {
        if (command == "info") return jade::cli::cmd_info(argc, argv);
        if (command == "bake") return jade::cli::cmd_bake(argc, argv);
        if (command == "bench" && argc > 2 && !std::strcmp(argv[2], "render") && !has_scene_flag(argc, argv))
            return jade::cli::cmd_bench_render(argc, argv);
        if (command == "bench" && argc > 2 && !std::strcmp(argv[2], "deform"))
            return jade::cli::cmd_bench_deform(argc, argv);
        if (command == "bench") return jade::cli::cmd_bench(argc, argv);
        if (command == "render") return jade::cli::cmd_render(argc, argv);
        if (command == "figure1") return jade::cli::cmd_figure1(argc, argv);
        if (command == "report") return jade::cli::cmd_report(argc, argv);
        if (command == "deform") return jade::cli::cmd_deform(argc, argv);
        if (command == "plan") return jade::cli::cmd_plan(argc, argv);
        if (command == "scene") return jade::cli::cmd_scene(argc, argv);
        if (command == "fidelity") return jade::cli::cmd_fidelity(argc, argv);
        if (command == "view") return exec_viewer(argc, argv);
        std::fprintf(stderr, "jade: unknown command '%s'\n\n%s", command.c_str(), kUsage);
        return 2;
    } catch (const jade::cli::UsageError& e) {
        std::fprintf(stderr, "%s\n(see: jade %s --help)\n", e.what(), command.c_str());
        return 2;
    } catch (const jade::Error& e) {
        std::fprintf(stderr, "jade %s: error: %s\n", command.c_str(), e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "jade %s: internal error: %s\n", command.c_str(), e.what());
        return 3;
    }
}
