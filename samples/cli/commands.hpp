// commands.hpp - the subcommands of the jade sample and what they share.
#pragma once

#include "args.hpp"

#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>

#include <memory>
#include <string>
#include <vector>

namespace jade::cli {

int cmd_info(int argc, char** argv);
int cmd_bake(int argc, char** argv);
int cmd_bench(int argc, char** argv);
int cmd_render(int argc, char** argv);
int cmd_figure1(int argc, char** argv);
int cmd_bench_render(int argc, char** argv);
int cmd_report(int argc, char** argv);
int cmd_deform(int argc, char** argv);

// Options most commands take.
std::vector<OptionSpec> device_options();
std::vector<OptionSpec> material_options();
std::vector<OptionSpec> bake_options();

std::unique_ptr<Context> make_context(const Args& args);
/// The material named by --material (default "jade") for `mesh`: physical presets use
/// --mm-per-unit, by default 100 / diagonal (the object is taken to be 10 cm across).
Material material_from_args(const Args& args, const PreparedMesh& mesh);
BakeSettings bake_settings_from_args(const Args& args);
/// The built-in default scene when `path` is empty or "bunny": the Stanford bunny if
/// assets/ has it, else a procedural sphere.
TriangleMesh load_mesh_arg(const std::string& path);

std::string format_ms(double ms);

}  // namespace jade::cli
