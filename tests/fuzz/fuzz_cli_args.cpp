// libFuzzer target for the command line of `jade bake` and `jade info`, without the GPU.
//
// The input is split into words at whitespace and NUL bytes; the first word picks the command
// ("info", anything else is "bake") and the rest become argv[2..]. The target then runs what
// cmd_bake.cpp / cmd_info.cpp do with their arguments before they open a mesh or a Vulkan
// device: jade::cli::Args (samples/cli/args.cpp, compiled in) with the same option specs, the
// positional and --out checks, bake_settings_from_args and material_from_args (common.cpp, on a
// small procedural mesh), and additionally Args::vec3 / all / get_or on every option given.
//
// Expected outcome for a bad command line: a jade::cli::UsageError (the CLI exits with code 2)
// whose message starts with "jade <command>: ". Findings: crashes, sanitizer reports, any other
// exception type, a plain jade::Error (exit code 1 for a command-line mistake), a message that
// does not start that way.
#include "args.hpp"
#include "commands.hpp"

#include <jade/mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace {

const jade::PreparedMesh* g_mesh = nullptr;

[[noreturn]] void finding(const char* what, const std::string& detail)
{
    std::fprintf(stderr, "\n==jade-fuzz== FINDING: %s\n%s\n", what, detail.c_str());
    std::fflush(stderr);
    std::abort();
}

std::vector<std::string> split(const uint8_t* data, size_t size)
{
    std::vector<std::string> words;
    std::string word;
    for (size_t i = 0; i < size; ++i) {
        const char c = char(data[i]);
        if (c == '\0' || c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            if (!word.empty()) words.push_back(std::move(word));
            word.clear();
        } else {
            word += c;
        }
    }
    if (!word.empty()) words.push_back(std::move(word));
    return words;
}

using jade::cli::Args;
using jade::cli::OptionSpec;

/// Every accessor on every declared option: they must throw nothing but UsageError.
void touch_all(const Args& args, const std::vector<OptionSpec>& specs)
{
    for (const auto& s : specs) {
        (void)args.flag(s.name);
        (void)args.get_or(s.name, "");
        (void)args.all(s.name);
        try {
            (void)args.vec3(s.name);
        } catch (const jade::cli::UsageError&) {
        }
    }
}

/// The command's Args with every accessor touched; nothing after --help (the command prints
/// the help and stops).
std::optional<Args> parse(const char* command, const std::vector<OptionSpec>& specs, int argc, char** argv)
{
    Args args(command, specs, argc, argv, 2);
    touch_all(args, specs);
    if (args.flag("help")) {
        (void)args.help();
        return std::nullopt;
    }
    return args;
}

void run_bake(int argc, char** argv)
{
    using namespace jade::cli;
    const auto parsed = parse("bake",
                              all_options({device_options(),
                                           material_options(),
                                           bake_options(),
                                           {{"out", "FILE", "output .glb or .gltf (required)"}}}),
                              argc, argv);
    if (!parsed) return;
    const Args& args = *parsed;
    if (args.positional().size() != 1) args.fail("expects exactly one MESH");
    if (!args.get("out")) args.fail("--out FILE is required");
    (void)bake_settings_from_args(args);
    (void)material_from_args(args, *g_mesh);
}

void run_info(int argc, char** argv)
{
    using namespace jade::cli;
    const auto args =
        parse("info", all_options({device_options(), {{"materials", "", "list the material presets"}}}), argc, argv);
    if (args && args->positional().size() > 1) args->fail("takes at most one mesh");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    static const jade::PreparedMesh mesh = jade::prepare_mesh(jade::procedural::sphere(1.0f, 4, 8));
    g_mesh = &mesh;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    auto words = split(data, size);
    const std::string command = !words.empty() && words[0] == "info" ? "info" : "bake";
    if (!words.empty()) words.erase(words.begin());
    std::vector<std::string> storage = {"jade", command};
    storage.insert(storage.end(), words.begin(), words.end());
    std::vector<char*> argv;
    for (auto& s : storage) argv.push_back(s.data());
    argv.push_back(nullptr);
    const int argc = int(storage.size());
    try {
        if (command == "info")
            run_info(argc, argv.data());
        else
            run_bake(argc, argv.data());
    } catch (const jade::cli::UsageError& e) {
        const std::string message = e.what();
        if (message.rfind("jade " + command + ": ", 0) != 0)
            finding("usage message does not name the command", message);
    } catch (const jade::Error& e) {
        finding("a command-line mistake raised jade::Error (exit code 1) instead of UsageError (2)", e.what());
    }
    return 0;
}
