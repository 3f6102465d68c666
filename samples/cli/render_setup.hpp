// render_setup.hpp - what `jade render`, `jade figure1` and `jade bench render` share (render_setup.cpp).
#pragma once

#include "commands.hpp"

#include <jade/render.hpp>

#include <string>
#include <utility>
#include <vector>

namespace jade::cli {

OptionSpec eval_option();                            ///< --eval: the tm mode's evaluation path
OptionSpec light_path_option();                      ///< --light-path: where tm reads a back light's path
std::vector<OptionSpec> render_options();            ///< jade render's and figure1's own options
RendererOptions renderer_options(const Args& args);  ///< from --eval and --light-path
std::pair<uint32_t, uint32_t> parse_size(const Args& args, const std::string& fallback);  ///< --size WxH
/// The camera of --eye, --target, --up, --fov, --frame (default: framed from +z).
Camera camera_from_args(const Args& args, const PreparedMesh& mesh, float aspect);
/// --lights PRESET: default | figure1 | back.
std::vector<Light> preset_lights(const Args& args, const Camera& camera);
/// --light SPEC (repeatable), else --lights.
std::vector<Light> lights_from_args(const Args& args, const Camera& camera);

// The mesh with its t_m per bake vertex: read from a baked file, or baked now (only for the
// modes that use it).
struct MeshScene {
    TriangleMesh mesh;
    PreparedMesh prepared;
    Material material;
    std::vector<glm::vec3> tm;     ///< per bake vertex when baked here, else empty
    std::vector<float> thickness;  ///< per bake vertex when baked here with transmission, else empty
    std::vector<glm::vec3> scattering_normal, normal_spread;  ///< per bake vertex when baked here, else empty
};

/// Gives the renderer the mesh, its bake and the material.
void set_scene(Renderer& renderer, const MeshScene& s);
/// Loads the mesh (a baked file's t_m and thickness are checked and used) and bakes it when
/// `need_tm` and the file has no bake.
MeshScene load_scene(const Args& args, Context& ctx, const std::string& path, bool need_tm);

}  // namespace jade::cli
