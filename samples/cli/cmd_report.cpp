// jade report MESH... --out DIR: the error of every approximation (AO rays and sampling, t_m
// far field ε, presets, LUT size, final image) against its GPU and wall time, in one run.
// Writes DIR/report.csv (rewritten after every configuration, atomically), DIR/summary.md and,
// through samples/report/plot_report.py, DIR/*.png.
#include "report.hpp"

#include <jade/dev/context.hpp>
#include <jade/dev/clock.hpp>
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <sstream>

namespace jade::cli {

namespace report {

Plan make_plan(const std::string& name, uint32_t tm_sample, std::vector<float> epsilons)
{
    Plan p;
    p.name = name;
    p.tm_sample = tm_sample;
    if (name == "tiny") {  // seconds on a ~1k-vertex mesh: for tests
        p.ao_rays = {4, 16, 64};
        p.ao_reference_rays = 1024;
        p.ao_distances = {0.1f};
        p.ao_agreement_rays = 16;
        p.tm_epsilons = epsilons.empty() ? std::vector<float>{1.6f, 0.8f, 0.4f} : epsilons;
        p.tm_jade = false;
        p.tm_grey_d = {0.05};
        p.lut_sizes = {16, 64};
        p.image_size = 64;
        p.deform_frames = 3;
        p.deform_slices = {2};
        return p;
    }
    p.ao_rays = {4, 8, 16, 32, 64, 128, 256, 512, 1024};
    p.ao_distances = {0.05f, 0.1f, 0.2f};
    // ε is the far field's opening ratio (shaders/tm_cluster.comp): below ~0.25 the clustered
    // pass costs more than the all-pairs one. The presets' own values are always included.
    p.tm_epsilons = epsilons.empty() ? std::vector<float>{1.6f, 1.2f, 0.8f, 0.6f, 0.4f, 0.25f} : epsilons;
    for (Quality q : {Quality::Draft, Quality::Default, Quality::High})
        p.tm_epsilons.push_back(BakeSettings::preset(q).tm_opening_ratio);
    std::sort(p.tm_epsilons.begin(), p.tm_epsilons.end(), std::greater<>());
    p.tm_epsilons.erase(std::unique(p.tm_epsilons.begin(), p.tm_epsilons.end()), p.tm_epsilons.end());
    p.tm_grey_d = {0.01, 0.05, 0.2};
    p.lut_sizes = {16, 32, 64, 128, 256, 512, 1024};
    if (name == "quick") {  // no 1024 rays, i.i.d. only at the default distance
        p.ao_rays.pop_back();
        p.iid_every_distance = false;
    }
    return p;
}

}  // namespace report

namespace {

namespace fs = std::filesystem;
using namespace report;
using Clock = std::chrono::steady_clock;

/// `relative` (a file or folder of the source tree) in the nearest folder above the executable's
/// (a build folder inside the tree) or above the working folder that holds it; empty if none.
fs::path find_in_tree(const fs::path& relative)
{
    std::error_code ec;
    for (fs::path start : {fs::read_symlink("/proc/self/exe", ec).parent_path(), fs::current_path(ec)})
        for (fs::path dir = start; !dir.empty(); dir = dir.parent_path()) {
            if (fs::exists(dir / relative, ec)) return dir / relative;
            if (dir == dir.parent_path()) break;
        }
    return {};
}

std::vector<std::string> default_meshes()
{
    std::vector<std::string> out{"bunny"};
    const char* assets = std::getenv("JADE_ASSETS");
    const fs::path name = "ChineseDragon-10kv.off";
    const fs::path dragon = assets && *assets ? fs::path(assets) / name : find_in_tree(fs::path("assets") / name);
    if (!dragon.empty() && fs::exists(dragon))
        out.push_back(dragon.string());
    else
        std::fprintf(stderr,
                     "jade report: the dragon is left out: no %s in $JADE_ASSETS or in an assets/ folder above "
                     "the executable or the working folder (third_party/fetch_assets.sh puts it there)\n",
                     name.string().c_str());
    return out;
}

/// samples/report/plot_report.py: $JADE_REPORT_PLOT, else find_in_tree.
fs::path find_plot_script()
{
    if (const char* env = std::getenv("JADE_REPORT_PLOT"); env && *env) return env;
    return find_in_tree(fs::path("samples") / "report" / "plot_report.py");
}

std::string shell_quote(const std::string& s)
{
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

void run_plots(const fs::path& dir)
{
    const fs::path script = find_plot_script();
    const std::string manual = "python3 " +
                               shell_quote(script.empty() ? "samples/report/plot_report.py" : script.string()) + " " +
                               shell_quote(dir.string());
    if (script.empty() || std::system("command -v python3 > /dev/null 2>&1") != 0) {
        std::fprintf(stderr, "plots: %s; draw them with: %s\n",
                     script.empty() ? "samples/report/plot_report.py not found" : "python3 not found", manual.c_str());
        return;
    }
    std::fprintf(stderr, "plots: %s\n", manual.c_str());
    if (std::system(manual.c_str()) != 0)
        std::fprintf(stderr, "plots: the script failed; run it again with: %s\n", manual.c_str());
}

/// "a,b,c" → numbers in (0, 100]; empty when the option is not given.
std::vector<float> epsilon_list(const Args& args)
{
    std::vector<float> out;
    const auto v = args.get("epsilons");
    if (!v) return out;
    std::stringstream ss(*v);
    for (std::string part; std::getline(ss, part, ',');) {
        char* end = nullptr;
        const double x = std::strtod(part.c_str(), &end);
        if (part.empty() || end != part.c_str() + part.size() || !(x > 0 && x <= 100))
            args.fail("--epsilons: '" + part + "' is not a number in (0, 100] (expected a list such as 1.2,0.8,0.4)");
        out.push_back(float(x));
    }
    if (out.empty()) args.fail("--epsilons: empty list");
    return out;
}

std::string describe(const Row& r)
{
    if (r.knob.empty()) return r.notes;
    std::string s = std::isnan(r.err.max)
                        ? r.notes
                        : "rms " + num(r.err.rms) + ", p99 " + num(r.err.p99) + ", max " + num(r.err.max);
    if (!std::isnan(r.gpu_ms)) s += " | GPU " + format_ms(r.gpu_ms);
    if (!std::isnan(r.wall_ms)) s += " | wall " + format_ms(r.wall_ms);
    return s;
}

}  // namespace

int cmd_report(int argc, char** argv)
{
    // This command's own options (the shared groups: commands.hpp).
    const std::vector<OptionSpec> own = {
        {"out", "DIR", "output folder (created): report.csv, summary.md, *.png"},
        {"quick", "", "skip 1024 rays and i.i.d. rays at max distances other than 0.1"},
        {"tiny", "", "a few configurations with a 1024-ray AO reference (tests, small meshes)"},
        {"sample", "N", "vertices the float64 t_m reference runs on (default 300)"},
        {"epsilons", "LIST", "clustered t_m epsilons, e.g. 1.2,0.8,0.4 (default 1.6..0.25 and the presets')"},
        {"no-plot", "", "do not run samples/report/plot_report.py"},
        {"summary-only", "", "measure nothing: rewrite summary.md and the plots from DIR/report.csv"}};
    Args args("report", all_options({device_options(), own}), argc, argv, 2);
    if (print_help(args, "usage: jade report [MESH...] --out DIR [--quick | --tiny]\n\n"
                         "Measures each approximation's error against its GPU and wall time. MESH defaults to the\n"
                         "bunny and assets/ChineseDragon-10kv.off (when present). Progress goes to stderr."))
        return 0;
    const auto out = args.get("out");
    if (!out || out->empty()) args.fail("--out DIR is required (the folder for report.csv, summary.md and the plots)");
    if (args.flag("quick") && args.flag("tiny")) args.fail("--quick and --tiny exclude each other");
    const Plan plan = make_plan(args.flag("tiny")    ? "tiny"
                                : args.flag("quick") ? "quick"
                                                     : "full",
                                args.count("sample", 300, 1, 1u << 24), epsilon_list(args));
    const fs::path dir = *out;
    check_output_folder("out", dir);
    std::error_code ec;

    if (args.flag("summary-only")) {
        auto ctx = make_context(args);
        dev::write_file_atomically(dir / "summary.md",
                                   summary_markdown(read_csv(dir / "report.csv"), plan, dev::device_info(*ctx).name));
        if (!args.flag("no-plot")) run_plots(dir);
        return 0;
    }
    const std::vector<std::string> sources = args.positional().empty() ? default_meshes() : args.positional();
    for (const auto& m : sources)  // before any measuring: a typo must not cost a half-hour run
        if (m != "bunny" && !fs::is_regular_file(m, ec)) throw Error(m + ": no such mesh file");
    auto ctx = make_context(args);
    Baker baker(*ctx);
    Session session{*ctx, baker, plan};
    std::vector<MeshState> states(sources.size());  // never resized: steps hold references
    std::vector<Step> steps;                        // destroyed before the context
    for (size_t m = 0; m < sources.size(); ++m) {
        states[m].source = sources[m];
        const size_t first = steps.size();
        add_bake_steps(session, states[m], steps);
        add_image_steps(session, states[m], steps);
        add_deform_steps(session, states[m], steps);
        for (size_t k = first; k < steps.size(); ++k)
            steps[k].what = fs::path(sources[m]).stem().string() + ": " + steps[k].what;
    }
    add_lut_steps(session, steps);

    std::fprintf(stderr, "jade report: %zu steps (plan %s) on %s; writing %s\n", steps.size(), plan.name.c_str(),
                 dev::device_info(*ctx).name.c_str(), dir.string().c_str());
    warm_up(session);
    std::vector<Row> rows;
    const auto t0 = Clock::now();
    for (size_t k = 0; k < steps.size(); ++k) {
        Row r = steps[k].run();
        std::fprintf(stderr, "[%zu/%zu] %s: %s\n", k + 1, steps.size(), steps[k].what.c_str(), describe(r).c_str());
        if (r.knob.empty()) continue;
        rows.push_back(std::move(r));
        dev::write_file_atomically(dir / "report.csv", csv(rows));
    }
    steps.clear();
    dev::write_file_atomically(dir / "summary.md", summary_markdown(rows, plan, dev::device_info(*ctx).name));
    std::fprintf(stderr, "jade report: %zu configurations in %s: %s, %s\n", rows.size(),
                 format_ms(ms_since(t0)).c_str(), (dir / "report.csv").string().c_str(),
                 (dir / "summary.md").string().c_str());
    if (!args.flag("no-plot")) run_plots(dir);
    // How close the shading modes come to the committed path-traced references (when this runs
    // from the repository, where they are).
    const fs::path references = find_in_tree(fs::path("tools") / "groundtruth" / "references");
    if (references.empty()) {
        std::fprintf(stderr, "jade report: the fidelity section is left out: no tools/groundtruth/references above the "
                             "executable or the working folder (run from a checkout of Jade)\n");
    } else {
        const std::string md = (dir / "fidelity.md").string(), json = (dir / "fidelity.json").string();
        std::vector<std::string> words = {"jade",   "fidelity", "--markdown",   md,
                                          "--json", json,       "--references", references.string()};
        if (args.get("device")) words.insert(words.end(), {"--device", *args.get("device")});
        std::vector<char*> argv2;
        for (auto& w : words) argv2.push_back(w.data());
        cmd_fidelity(int(argv2.size()), argv2.data());
    }
    return 0;
}

}  // namespace jade::cli
