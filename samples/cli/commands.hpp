// commands.hpp - the subcommands of the jade sample and what they share.
#pragma once

#include "args.hpp"

#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/io.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/scene.hpp>

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace jade::cli {

/// A subcommand: `jade NAME ...` with the whole command line; returns the exit status.
using Command = int(int argc, char** argv);
Command cmd_info;
Command cmd_bake;
Command cmd_bench;
Command cmd_render;
Command cmd_figure1;
Command cmd_bench_render;
Command cmd_report;
Command cmd_deform;
Command cmd_bench_deform;
Command cmd_plan;
Command cmd_scene;
Command cmd_fidelity;

// Options most commands take.
std::vector<OptionSpec> device_options();
std::vector<OptionSpec> material_options();
std::vector<OptionSpec> bake_options();
/// --allow-outside-links: what the readers may follow (ReadOptions).
std::vector<OptionSpec> input_options();
/// The ReadOptions of --allow-outside-links.
ReadOptions read_options(const Args& args);
/// A command's options: the groups in order, e.g. all_options({device_options(), bake_options(),
/// {{"out", "FILE", "output file"}}}).
std::vector<OptionSpec> all_options(std::initializer_list<std::vector<OptionSpec>> groups);

/// Prints `usage` (the synopsis and what the command does), a blank line and the options to stdout.
void print_usage(const Args& args, const char* usage);
/// With --help: prints the usage (print_usage) and returns true, and the command exits with 0.
bool print_help(const Args& args, const char* usage);

std::unique_ptr<Context> make_context(const Args& args);
/// The material named by --material (default "jade") for `mesh`: physical presets use
/// --mm-per-unit, by default 100 / diagonal (the object is taken to be 10 cm across).
Material material_from_args(const Args& args, const PreparedMesh& mesh, const std::optional<Material>& baked = {});
/// The same for an object (or a whole asset) whose bounding box has this diagonal (mesh units).
/// `baked`, the material a file was baked with (ReadOptions::baked_material), is used instead of
/// the default when none of --material, --medium and --mm-per-unit is given; --d, --strength and
/// --no-transmission apply to either.
Material material_from_args(const Args& args, double diagonal, const std::optional<Material>& baked = {});
BakeSettings bake_settings_from_args(const Args& args);
/// The built-in default scene when `path` is empty or "bunny": the Stanford bunny if
/// assets/ has it, else a procedural sphere.
/// What the reader repaired (ReadOptions::warnings) is printed as "jade: warning: ...".
TriangleMesh load_mesh_arg(const std::string& path, const ReadOptions& options = {});
/// A file of the test meshes (third_party/fetch_assets.sh) by name, from $JADE_ASSETS, ./assets or
/// the source tree's assets/, whatever the working directory; empty when none has it.
std::filesystem::path find_asset(const std::string& name);

/// Checks an output file named by --FLAG before any work is done (a bake must not run for
/// nothing): the extension is one of `extensions` (lower case, with the dot; else a usage
/// error, exit 2), the path is not a folder, its folder exists, and a file can be created
/// there (else jade::Error, exit 1). Leaves nothing behind.
void check_output_file(const Args& args, const std::string& flag, const std::filesystem::path& path,
                       const std::vector<std::string>& extensions);
/// Creates the output folder named by --FLAG if needed and checks that a file can be created in
/// it (jade::Error otherwise).
void check_output_folder(const std::string& flag, const std::filesystem::path& folder);

std::string format_ms(double ms);
/// The q-quantile (0 = min, 0.5 = median, 1 = max) of a non-empty sample, nearest rank.
double quantile(std::vector<double> v, double q);

// Scenes (cmd_scene.cpp): --cache, --mode and the bake options as SceneSettings.
std::vector<OptionSpec> scene_options();
SceneSettings scene_settings_from_args(const Args& args);

}  // namespace jade::cli
