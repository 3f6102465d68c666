#include "commands.hpp"

#include <jade/dev/io.hpp>
#include <jade/dev/material.hpp>
#include <jade/dev/names.hpp>
#include <jade/io.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace jade::cli {

std::vector<OptionSpec> device_options()
{
    return {{"device", "NAME", "use the Vulkan device whose name contains NAME (or JADE_DEVICE)"},
            {"validation", "", "enable the Khronos validation layer (or JADE_VALIDATION=1)"},
            {"verbose", "", "say which device and passes run"}};
}

std::vector<OptionSpec> material_options()
{
    return {{"material", "NAME", "material preset (default jade); see jade info --materials"},
            {"mm-per-unit", "X", "millimetres per mesh unit (default: the object is 100 mm across)"},
            {"d", "F", "Burley profile: mean scattering distance d as a fraction of the diagonal"},
            {"strength", "S", "Gaussian variance per unit t_m (rad^2; default: the material's)"},
            {"medium", "SR,SG,SB:AR,AG,AB[:G]",
             "a physical medium instead of --material: scattering and absorption "
             "coefficients per mesh unit (linear RGB) and the HG mean cosine g"},
            {"ior", "N", "with --medium: the boundary's relative index of refraction (default 1.5)"},
            {"roughness", "R", "with --medium: the boundary's GGX roughness, alpha = R^2 as in glTF (default 0.6)"},
            {"no-transmission", "", "leave out the light through thin parts (the poster's model alone)"}};
}

std::vector<OptionSpec> bake_options()
{
    return {{"quality", "Q", "draft | default | high (AO rays and t_m accuracy)"},
            {"ao-rays", "N", "AO rays per vertex (overrides the quality's)"},
            {"ao-iid", "", "i.i.d. rays instead of Hammersley + Cranley-Patterson rotation"},
            {"ao-distance", "F", "AO max hit distance, fraction of the diagonal (default 0.1)"},
            {"ao-epsilon", "F", "AO ray origin offset, fraction of the diagonal (default 1e-4)"},
            {"seed", "N", "AO random seed (default 1)"},
            {"method", "M", "t_m far field: auto | exact | clustered | grid"},
            {"grid-resolution", "C", "grid far field: cells per Gaussian sigma, 1.5..4 (draft 1.5, default 2, high 3)"},
            {"epsilon", "T", "t_m far-field opening ratio theta (0.3: ~2e-5 error, 1: ~2e-3)"}};
}

std::vector<OptionSpec> input_options()
{
    return {{"allow-outside-links", "",
             "read a glTF's buffers and images through symbolic links that lead out of its folder (off: a baked "
             "asset must not carry other files of this machine)"}};
}

ReadOptions read_options(const Args& args)
{
    ReadOptions options;
    options.allow_outside_links = args.flag("allow-outside-links");
    return options;
}

std::vector<OptionSpec> all_options(std::initializer_list<std::vector<OptionSpec>> groups)
{
    std::vector<OptionSpec> out;
    for (const auto& g : groups) out.insert(out.end(), g.begin(), g.end());
    return out;
}

void print_usage(const Args& args, const char* usage) { std::printf("%s\n\n%s", usage, args.help().c_str()); }

bool print_help(const Args& args, const char* usage)
{
    if (!args.flag("help")) return false;
    print_usage(args, usage);
    return true;
}

std::unique_ptr<Context> make_context(const Args& args)
{
    ContextOptions o;
    o.device = args.get_or("device", "");
    o.validation = args.flag("validation");
    o.verbose = args.flag("verbose");
    return std::make_unique<Context>(o);
}

Medium medium_from_args(const Args& args)
{
    const std::string spec = args.get_or("medium", "");
    auto fail = [&](const std::string& why) {
        args.fail("--medium " + spec + ": " + why + " (expected SR,SG,SB:AR,AG,AB[:G], coefficients per mesh unit)");
    };
    std::vector<std::string> parts;
    std::stringstream ss(spec);
    for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
    if ((parts.size() != 2 && parts.size() != 3) || spec.back() == ':') fail("need two or three ':'-separated parts");
    auto number = [&](const std::string& text, const char* what) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end || !std::isfinite(v))
            fail(std::string(what) + " '" + text + "' is not a finite number");
        return v;
    };
    auto rgb = [&](const std::string& text, const char* what) {
        const auto v = Args::triple(text);
        if (!v) fail(std::string(what) + " '" + text + "' is not three finite comma-separated numbers");
        return glm::dvec3((*v)[0], (*v)[1], (*v)[2]);
    };
    Medium m;
    m.sigma_s = rgb(parts[0], "sigma_s");
    m.sigma_a = rgb(parts[1], "sigma_a");
    if (parts.size() == 3) m.g = number(parts[2], "g");
    // The boundary's relative index of refraction, as Material::from_medium takes it: (0.2, 5).
    m.ior = args.number("ior", m.ior, 0.2, 5.0);
    if (m.ior == 0.2 || m.ior == 5.0) args.fail("--ior: " + args.get_or("ior", "") + " is out of range (0.2, 5)");
    m.roughness = args.number("roughness", m.roughness, 0.0, 1.0);
    return m;
}

Material material_from_args(const Args& args, const PreparedMesh& mesh, const std::optional<Material>& baked)
{
    return material_from_args(args, double(mesh.diagonal), baked);
}

namespace {

/// The bake runs in single precision on a mesh scaled to about unit size: a profile far smaller
/// or far larger than the object underflows or overflows there (R's 1/d³, the dipole's depths
/// squared, a Gaussian's variance) and gives NaN. Beyond these ratios t_m has long reached its
/// limits (1: the object is all near field; 0: the light leaves before it scatters back), so
/// nothing is lost by refusing, the same range as --d's.
constexpr double kMinProfileRatio = 1e-9, kMaxProfileRatio = 1e9;

void check_profile_scale(const Args& args, const Material& m, double diagonal, double mm_per_unit)
{
    if (!(diagonal > 0.0) || !std::isfinite(diagonal)) return;  // the mesh checks name that
    for (int c = 0; c < 3; ++c) {
        const double radius = dev::radius_for_tail(m.profile[c], 0.5);  // the median scattering radius
        const double ratio = radius / diagonal;
        if (ratio >= kMinProfileRatio && ratio <= kMaxProfileRatio) continue;
        char text[320];
        std::snprintf(text, sizeof text,
                      "material %s: its median scattering radius (channel %d: %.3g units) is %.3g times the "
                      "object's diagonal (%.3g units), outside [%g, %g]: t_m would not be finite in single precision",
                      m.name.c_str(), c, radius, ratio, diagonal, kMinProfileRatio, kMaxProfileRatio);
        if (args.get("medium")) args.fail(std::string("--medium: ") + text);
        if (args.get("d")) args.fail(std::string("--d: ") + text);
        char mm[64];
        std::snprintf(mm, sizeof mm, "%g", mm_per_unit);
        args.fail(std::string("--mm-per-unit ") + mm + ": " + text + " (the object would be " + [&] {
            char s[32];
            std::snprintf(s, sizeof s, "%.3g", diagonal * mm_per_unit);
            return std::string(s);
        }() + " mm across)");
    }
}

}  // namespace

Material material_from_args(const Args& args, double diagonal, const std::optional<Material>& baked)
{
    double default_mm = diagonal > 0 ? 100.0 / diagonal : 1.0;
    double mm_per_unit = args.number("mm-per-unit", default_mm, 1e-30, 1e30);
    Material m;
    if (args.get("medium") && args.get("material")) args.fail("--medium and --material: give one of them");
    if (!args.get("medium") && (args.get("ior") || args.get("roughness")))
        args.fail("--ior and --roughness describe a --medium's boundary; give --medium too");
    try {
        if (args.get("medium"))
            m = Material::from_medium(medium_from_args(args), "medium");
        else if (baked && !args.get("material") && !args.get("mm-per-unit"))
            m = *baked;
        else
            m = material_preset(args.get_or("material", "jade"), mm_per_unit);
    } catch (const UsageError&) {
        throw;  // already names its flag
    } catch (const Error& e) {
        // An unknown --material or a bad medium is a command-line mistake: exit code 2, naming the flag.
        args.fail(std::string(args.get("medium") ? "--medium: " : "--material: ") + e.what());
    }
    if (args.flag("no-transmission")) m.transmission.weight = m.transmission.diffusion_weight = 0.0f;
    if (auto d = args.get("d")) {
        double rel = args.number("d", 0.05, 1e-9, 1e9);
        // Keep the preset's colour ratios, scale so the channels' mean d is rel × diagonal.
        double mean = 0;
        for (auto& p : m.profile) mean += (p.kind == ProfileKind::Burley ? p.d : 1.0) / 3.0;
        for (auto& p : m.profile)
            p = ChannelProfile::burley((p.kind == ProfileKind::Burley ? p.d / mean : 1.0) * rel * diagonal);
    }
    m.strength = float(args.number("strength", m.strength, 0.0, 1e6));
    check_profile_scale(args, m, diagonal, mm_per_unit);
    return m;
}

BakeSettings bake_settings_from_args(const Args& args)
{
    const std::string q = args.get_or("quality", "default");
    Quality quality = Quality::Default;
    try {
        quality = dev::parse_quality(q);
    } catch (const Error&) {
        args.fail("--quality: '" + q + "' is not one of draft, default, high");
    }
    BakeSettings s = BakeSettings::preset(quality);
    s.ao.rays = args.count("ao-rays", s.ao.rays, 1, 65536);
    s.ao.low_discrepancy = !args.flag("ao-iid");
    s.ao.max_distance_rel = float(args.number("ao-distance", s.ao.max_distance_rel, 1e-6, 1e6));
    s.ao.ray_offset_rel = float(args.number("ao-epsilon", s.ao.ray_offset_rel, 0.0, 1.0));
    s.ao.seed = args.count("seed", s.ao.seed, 0, 0xffffffffu);
    const std::string method = args.get_or("method", "auto");
    try {
        s.method = dev::parse_tm_method(method);
    } catch (const Error&) {
        args.fail("--method: '" + method + "' is not one of auto, exact, clustered, grid");
    }
    s.tm_opening_ratio = float(args.number("epsilon", s.tm_opening_ratio, 1e-6, 4.0));
    s.tm_grid_resolution = float(args.number("grid-resolution", s.tm_grid_resolution, 1.5, 4.0));
    return s;
}

std::filesystem::path find_asset(const std::string& name)
{
    namespace fs = std::filesystem;
    // Wherever jade runs from: $JADE_ASSETS, the working directory's assets/, then the source
    // tree's (next to the executable's build tree, build/samples/cli/jade, or where it was
    // configured from).
    std::vector<fs::path> folders;
    if (const char* assets = std::getenv("JADE_ASSETS")) folders.emplace_back(assets);
    folders.emplace_back("assets");
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) folders.push_back(exe.parent_path() / "../../../assets");
    folders.emplace_back(JADE_CLI_SOURCE_ASSETS);
    for (const fs::path& folder : folders)
        if (fs::is_regular_file(folder / name, ec)) return (folder / name).lexically_normal();
    return {};
}

TriangleMesh load_mesh_arg(const std::string& path, const ReadOptions& options)
{
    if (!path.empty() && path != "bunny") {
        std::vector<std::string> warnings;
        ReadOptions with_warnings = options;
        with_warnings.warnings = &warnings;
        TriangleMesh mesh = load_mesh(path, with_warnings);
        for (const auto& w : warnings) std::fprintf(stderr, "jade: warning: %s\n", w.c_str());
        return mesh;
    }
    const std::filesystem::path bunny = find_asset("bunny00.off");
    if (!bunny.empty()) return load_mesh(bunny);
    std::fprintf(stderr,
                 "jade: bunny00.off not found in $JADE_ASSETS, ./assets or %s (run third_party/fetch_assets.sh); "
                 "using a procedural sphere\n",
                 JADE_CLI_SOURCE_ASSETS);
    return procedural::sphere(1.0f, 64, 128);
}

namespace {

std::string lower(std::string s)
{
    for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

/// Creates and removes a temporary file beside `path` the way the writers do
/// (write_file_atomically: exclusively, under a name nobody can guess, never through a link):
/// permission bits do not stop root, a read-only or full file system does, so only a real
/// file tells. Throws jade::Error naming the flag and the folder.
void probe_writable(const std::string& flag, const std::filesystem::path& path, const std::filesystem::path& folder)
{
    try {
        dev::check_writable(path);
    } catch (const Error& e) {
        throw Error("--" + flag + " " + path.string() + ": cannot create a file in folder '" + folder.string() +
                    "': " + e.what());
    }
}

}  // namespace

void check_output_file(const Args& args, const std::string& flag, const std::filesystem::path& path,
                       const std::vector<std::string>& extensions)
{
    namespace fs = std::filesystem;
    const auto ext = lower(path.extension().string());
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
        std::string list;
        for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
        args.fail("--" + flag + " " + path.string() + ": unsupported extension '" + path.extension().string() +
                  "' (supported: " + list + ")");
    }
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw Error("--" + flag + " " + path.string() + ": is a folder, not a file");
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::exists(folder, ec))
        throw Error("--" + flag + " " + path.string() + ": folder '" + folder.string() + "' does not exist");
    if (!fs::is_directory(folder, ec))
        throw Error("--" + flag + " " + path.string() + ": '" + folder.string() + "' is not a folder");
    probe_writable(flag, path, folder);
}

void check_output_folder(const std::string& flag, const std::filesystem::path& folder)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder)) {
        const std::string why = ec ? ec.message() : "a file of that name exists";
        throw Error("--" + flag + " " + folder.string() + ": cannot create the folder: " + why);
    }
    probe_writable(flag, folder / "jade-write-probe", folder);
}

double quantile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    return v[size_t(std::lround(q * double(v.size() - 1)))];
}

std::string format_ms(double ms)
{
    char buf[32];
    if (ms < 1)
        std::snprintf(buf, sizeof buf, "%.3f ms", ms);
    else if (ms < 1000)
        std::snprintf(buf, sizeof buf, "%.1f ms", ms);
    else
        std::snprintf(buf, sizeof buf, "%.2f s", ms / 1000);
    return buf;
}

}  // namespace jade::cli
