// report_write.cpp - what `jade report` writes: report.csv and summary.md (tables per knob, the
// Pareto front of time against error, and the recommended settings per quality level).
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

namespace jade::cli::report {

std::string strf(const char* format, ...)
{
    va_list a, b;
    va_start(a, format);
    va_copy(b, a);
    const int n = std::vsnprintf(nullptr, 0, format, a);
    va_end(a);
    std::string out(size_t(std::max(n, 0)), '\0');
    std::vsnprintf(out.data(), out.size() + 1, format, b);
    va_end(b);
    return out;
}

std::string num(double x) { return std::isnan(x) ? "" : strf("%.3g", x); }

ErrorStats error_stats(std::vector<double> e)
{
    if (e.empty()) return {};
    std::sort(e.begin(), e.end());
    double sq = 0;
    for (double x : e) sq += x * x;
    const size_t rank = size_t(std::ceil(0.99 * double(e.size())));
    return {std::sqrt(sq / double(e.size())), e[std::max<size_t>(rank, 1) - 1], e.back()};
}

std::pair<std::string, std::string> split_method(const std::string& method)
{
    const size_t open = method.rfind(" (");
    if (open == std::string::npos || method.back() != ')') return {method, ""};
    return {method.substr(0, open), method.substr(open + 2, method.size() - open - 3)};
}

namespace {

std::string csv_field(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string csv_number(double x) { return std::isnan(x) ? "" : strf("%.6g", x); }

}  // namespace

std::string csv(const std::vector<Row>& rows)
{
    std::string out = "mesh,knob,value,method,gpu_ms,wall_ms,err_rms,err_p99,err_max,notes\n";
    for (const Row& r : rows) {
        out += csv_field(r.mesh) + "," + csv_field(r.knob) + "," + csv_field(r.value) + "," + csv_field(r.method) + ",";
        for (double x : {r.gpu_ms, r.wall_ms, r.err.rms, r.err.p99, r.err.max}) out += csv_number(x) + ",";
        out += csv_field(r.notes) + "\n";
    }
    return out;
}

std::vector<Row> read_csv(const std::filesystem::path& path)
{
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path.string() + ": cannot open (run jade report without --summary-only first)");
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string text = ss.str();
    std::vector<std::vector<std::string>> records(1, std::vector<std::string>(1));
    bool quoted = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"')
            records.back().back() += c, ++i;
        else if (c == '"')
            quoted = !quoted;
        else if (!quoted && c == ',')
            records.back().emplace_back();
        else if (!quoted && c == '\n')
            records.emplace_back(1);
        else
            records.back().back() += c;
    }
    const std::string header = "mesh,knob,value,method,gpu_ms,wall_ms,err_rms,err_p99,err_max,notes";
    if (text.compare(0, header.size(), header) != 0)
        throw Error(path.string() + ": not a jade report CSV (header differs)");
    auto number = [&](const std::string& s) { return s.empty() ? kNaN : std::strtod(s.c_str(), nullptr); };
    std::vector<Row> rows;
    for (size_t k = 1; k < records.size(); ++k) {
        const auto& f = records[k];
        if (f.size() == 1 && f[0].empty()) continue;  // the last line's end
        if (f.size() != 10) throw Error(path.string() + ": line " + std::to_string(k + 1) + ": expected 10 fields");
        rows.push_back(
            {f[0], f[1], f[2], f[3], number(f[4]), number(f[5]), {number(f[6]), number(f[7]), number(f[8])}, f[9]});
    }
    return rows;
}

namespace {

// ---- Pareto fronts ---------------------------------------------------------------------
// Within a group (same mesh, same family of knobs, same case), a row is on the front when no
// other row is at least as fast and at least as accurate and better in one. The axes per
// family (samples/report/plot_report.py uses the same):
//   AO (ao_rays)                     GPU time, RMS error        group: mesh, max distance
//   t_m (tm_exact/epsilon/auto)      GPU time, max error        group: mesh, material
//   presets end to end (quality)     GPU time, max error        group: mesh
//   LUT (lut_size, image_lut)        texels,   max error        group: mesh
//   deformation (deform_ao, _tm)     GPU time, RMS error        group: mesh, knob
struct Axes {
    std::string group;
    double x = kNaN, y = kNaN;
};

double texels(const std::string& wxh)
{
    unsigned w = 0, h = 0;
    return std::sscanf(wxh.c_str(), "%ux%u", &w, &h) == 2 ? double(w) * h : kNaN;
}

std::optional<Axes> pareto_axes(const Row& r)
{
    const std::string c = split_method(r.method).second;
    if (r.knob == "ao_rays") return Axes{r.mesh + "|ao|" + c, r.gpu_ms, r.err.rms};
    if (r.knob == "tm_exact" || r.knob == "tm_epsilon" || r.knob == "tm_grid_resolution" || r.knob == "tm_auto")
        return Axes{r.mesh + "|tm|" + c, r.gpu_ms, r.err.max};
    if (r.knob == "quality") return Axes{r.mesh + "|quality", r.gpu_ms, r.err.max};
    if (r.knob == "lut_size" || r.knob == "image_lut") return Axes{r.mesh + "|" + r.knob, texels(r.value), r.err.max};
    if (r.knob == "deform_ao" || r.knob == "deform_tm") return Axes{r.mesh + "|" + r.knob, r.gpu_ms, r.err.rms};
    return std::nullopt;
}

std::vector<bool> pareto_front(const std::vector<Row>& rows)
{
    std::vector<std::optional<Axes>> axes;
    for (const Row& r : rows) axes.push_back(pareto_axes(r));
    std::vector<bool> front(rows.size(), false);
    for (size_t i = 0; i < rows.size(); ++i) {
        if (!axes[i] || std::isnan(axes[i]->x) || std::isnan(axes[i]->y)) continue;
        front[i] = true;
        for (size_t j = 0; j < rows.size() && front[i]; ++j) {
            if (j == i || !axes[j] || axes[j]->group != axes[i]->group) continue;
            const Axes &a = *axes[i], &b = *axes[j];
            if (b.x <= a.x && b.y <= a.y && (b.x < a.x || b.y < a.y)) front[i] = false;
        }
    }
    return front;
}

// ---- Markdown ----------------------------------------------------------------------------

struct Table {
    std::vector<std::string> head;
    std::vector<std::vector<std::string>> body;
    std::string markdown() const
    {
        auto line = [this](const std::vector<std::string>& cells) {
            std::string s = "|";
            for (size_t i = 0; i < head.size(); ++i) s += " " + (i < cells.size() ? cells[i] : std::string()) + " |";
            return s + "\n";
        };
        std::string s = line(head) + "|";
        for (size_t i = 0; i < head.size(); ++i) s += "---|";
        s += "\n";
        for (const auto& row : body) s += line(row);
        return s + "\n";
    }
};

std::string ms(double x) { return std::isnan(x) ? "–" : format_ms(x); }
std::string bold_if(bool b, const std::string& s) { return b && !s.empty() ? "**" + s + "**" : s; }
std::string pct(double x) { return std::isnan(x) ? "–" : strf("%.3g %%", 100 * x); }

/// Distinct values of `key` over the rows, in first-seen order.
template <class F> std::vector<std::string> distinct(const std::vector<Row>& rows, F key)
{
    std::vector<std::string> out;
    for (const Row& r : rows)
        if (std::string k = key(r); !k.empty() && std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
    return out;
}

/// The standard table of one group: value, algorithm, times, the three errors.
std::string rows_table(const std::vector<Row>& rows, const std::vector<bool>& front, const std::vector<size_t>& pick,
                       const std::string& value_head, bool percent, bool with_notes)
{
    Table t{{value_head, "method", "GPU", "wall", "RMS", "p99", "max"}, {}};
    if (with_notes) t.head.push_back("notes");
    for (size_t i : pick) {
        const Row& r = rows[i];
        auto e = [&](double x) { return bold_if(front[i], percent ? pct(x) : num(x)); };
        std::vector<std::string> cells{bold_if(front[i], r.value),
                                       split_method(r.method).first,
                                       ms(r.gpu_ms),
                                       ms(r.wall_ms),
                                       e(r.err.rms),
                                       e(r.err.p99),
                                       e(r.err.max)};
        if (with_notes) cells.push_back(r.notes);
        t.body.push_back(cells);
    }
    return t.markdown();
}

std::vector<size_t> select(const std::vector<Row>& rows, const std::function<bool(const Row&)>& keep)
{
    std::vector<size_t> out;
    for (size_t i = 0; i < rows.size(); ++i)
        if (keep(rows[i])) out.push_back(i);
    return out;
}

bool is_tm(const Row& r)
{
    return r.knob == "tm_exact" || r.knob == "tm_epsilon" || r.knob == "tm_grid_resolution" || r.knob == "tm_auto";
}

// ---- Recommended settings ------------------------------------------------------------------

struct Target {
    const char* quality;
    Quality level;
    double ao_rms, tm_max;  ///< AO RMS (absolute), t_m max relative error
};
constexpr Target kTargets[] = {{"draft", Quality::Draft, 0.05, 0.05},
                               {"default", Quality::Default, 0.02, 0.01},
                               {"high", Quality::High, 0.01, 0.001}};

/// The cheapest configuration (GPU time summed over meshes and cases) among the rows `pick`
/// whose error (`err`, the worst over meshes and cases) meets `bound`. A configuration is the
/// row's value (and algorithm, when `per_algorithm`). Returns its key, or empty.
std::pair<std::string, std::string> cheapest(const std::vector<Row>& rows, const std::vector<size_t>& pick,
                                             double ErrorStats::*err, double bound, bool per_algorithm)
{
    std::map<std::pair<std::string, std::string>, std::pair<double, double>> cost_error;  // key → (ms, worst error)
    for (size_t i : pick) {
        const Row& r = rows[i];
        auto key = std::make_pair(r.value, per_algorithm ? split_method(r.method).first : std::string());
        auto& [t, e] = cost_error[key];
        t += r.gpu_ms;
        e = std::max(e, r.err.*err);
    }
    std::pair<std::string, std::string> best;
    double best_ms = INFINITY;
    for (const auto& [key, te] : cost_error)
        if (te.second <= bound && te.first < best_ms) best = key, best_ms = te.first;
    return best;
}

std::string recommended(const std::vector<Row>& rows, const Plan& plan)
{
    const auto meshes = distinct(rows, [](const Row& r) { return r.knob == "ao_rays" ? r.mesh : std::string(); });
    const std::string ao_case = strf("d=%g", double(plan.ao_default_distance));
    const auto ao_rows =
        select(rows, [&](const Row& r) { return r.knob == "ao_rays" && split_method(r.method).second == ao_case; });
    const auto eps_rows = select(rows, [](const Row& r) { return r.knob == "tm_epsilon"; });
    const auto first_material =
        distinct(rows, [](const Row& r) { return is_tm(r) ? split_method(r.method).second : std::string(); });
    std::string out;
    for (const Target& target : kTargets) {
        out += strf("### %s\n\nTargets: AO RMS ≤ %g (absolute), t_m max ≤ %g %% (relative, every material).\n\n",
                    target.quality, target.ao_rms, 100 * target.tm_max);
        Table t{{"part", "setting"}, {}};
        for (const auto& m : meshes) t.head.insert(t.head.end(), {m + ": error", m + ": GPU"});
        // One line: per mesh, the errors of the matching row with the largest max (the worst
        // material) and the GPU time of the first material's row.
        auto add =
            [&](std::string part, std::string setting, const std::function<bool(const Row&)>& match, bool percent) {
            std::vector<std::string> cells{part, setting};
            for (const auto& m : meshes) {
                const Row* worst = nullptr;
                double gpu = kNaN;
                for (const Row& r : rows)
                    if (r.mesh == m && match(r)) {
                        if (!worst || r.err.max > worst->err.max) worst = &r;
                        if (first_material.empty() || split_method(r.method).second == first_material[0] ||
                            r.knob == "ao_rays")
                            gpu = r.gpu_ms;
                    }
                auto f = [&](double x) { return percent ? pct(x) : num(x); };
                cells.push_back(!worst ? "not measured"
                                       : "RMS " + f(worst->err.rms) + ", p99 " + f(worst->err.p99) + ", max " +
                                             f(worst->err.max));
                cells.push_back(ms(gpu));
            }
            t.body.push_back(cells);
        };
        auto [rays, sampling] = cheapest(rows, ao_rows, &ErrorStats::rms, target.ao_rms, true);
        if (rays.empty())
            t.body.push_back({"AO", "no measured ray count meets the target"});
        else
            add(
                "AO", rays + " rays, " + sampling + " (" + ao_case + ")",
                [&](const Row& r) {
                return r.knob == "ao_rays" && r.value == rays && r.method == sampling + " (" + ao_case + ")";
                },
                false);
        const std::string eps = cheapest(rows, eps_rows, &ErrorStats::max, target.tm_max, false).first;
        if (eps.empty())
            add(
                "t_m (worst material)", "exact (all pairs): no measured ε meets the target",
                [](const Row& r) { return r.knob == "tm_exact"; }, true);
        else
            add(
                "t_m (worst material)", "clustered, ε = " + eps,
                [&](const Row& r) { return r.knob == "tm_epsilon" && r.value == eps; }, true);
        // The preset as measured (its row's notes), else as compiled in.
        const BakeSettings preset = BakeSettings::preset(target.level);
        std::string today = strf("%u rays, ε = %g", preset.ao.rays, double(preset.tm_opening_ratio));
        for (const Row& r : rows) {
            std::smatch m;
            static const std::regex measured("(\\d+) AO rays.*eps=([0-9.eE+-]+)");
            if (r.knob == "quality" && r.value == target.quality && std::regex_search(r.notes, m, measured)) {
                today = m[1].str() + " rays, ε = " + m[2].str();
                break;
            }
        }
        add(
            "today's preset end to end: t_m vs float64", today,
            [&](const Row& r) { return r.knob == "quality" && r.value == target.quality; }, true);
        add(
            "today's preset: final image (8-bit levels)", today,
            [&](const Row& r) { return r.knob == "image" && r.value == target.quality; }, false);
        out += t.markdown();
    }
    return out;
}

}  // namespace

std::string summary_markdown(const std::vector<Row>& rows, const Plan& plan, const std::string& device)
{
    const auto front = pareto_front(rows);
    const auto meshes = distinct(rows, [](const Row& r) { return r.mesh == "(any)" ? std::string() : r.mesh; });
    std::ostringstream md;
    md << "# Error against run time\n\n"
       << "Generated by `jade report` (plan: " << plan.name << ") on " << device << ". Meshes: ";
    for (size_t i = 0; i < meshes.size(); ++i) md << (i ? ", " : "") << meshes[i];
    md << ".\n\n"
       << "* **AO**: absolute per-vertex error against a " << plan.ao_reference_rays
       << "-ray **low-discrepancy GPU AO** of the same max distance (not the float64 reference, which "
          "is the same rays in double precision: see \"AO: GPU against float64\").\n"
       << "* **t_m**: relative per-vertex error (worst colour channel) against `reference_tm` (float64) on a "
          "fixed sample of **"
       << plan.tm_sample << " vertices** (evenly spread over the vertex order), all from the " << plan.ao_reference_rays
       << "-ray AO at d = " << plan.ao_default_distance
       << ", so only the far field and "
          "float32 are measured. The exact row is the float32 (compensated) against float64 error.\n"
       << "* **Times**: GPU = timestamp queries (`BakeTimings::gpu_stages`, summed), wall = the whole call "
          "(CPU tree and BVH builds, upload, read-back). One run each (AO passes under 300 ms: best of 3); "
          "other processes on the machine (parallel builds) make them noisy: compare within a table, not across runs.\n"
       << "* **Bold** rows are on the Pareto front of their table (no other row is both faster and more "
          "accurate): GPU time against RMS for AO, against max for t_m; texels against max for the LUT.\n\n";

    md << "## Recommended settings\n\nThe cheapest measured setting that meets each quality level's targets on every "
          "mesh (and, for t_m, every material), with its measured error and GPU time; then today's preset "
          "(`BakeSettings::preset`) end to end: its own AO and t_m on the first material, against float64 "
          "t_m from the reference AO, and its final image.\n\n"
       << recommended(rows, plan);

    for (const auto& m : meshes) {
        md << "## " << m << "\n\n### AO: rays per vertex, sampling, max distance\n\n";
        for (const auto& c : distinct(rows, [&](const Row& r) {
                 return r.mesh == m && r.knob == "ao_rays" ? split_method(r.method).second : "";
             })) {
            md << "Max distance " << c.substr(2) << " × diagonal; absolute error:\n\n";
            md << rows_table(rows, front,
                             select(
                                 rows,
                                 [&](const Row& r) {
                return r.mesh == m && r.knob == "ao_rays" && split_method(r.method).second == c;
                                 }),
                             "rays", false, false);
        }
        md << "### AO: GPU against float64 (`reference_ao`, same rays)\n\n"
           << rows_table(rows, front, select(rows, [&](const Row& r) { return r.mesh == m && r.knob == "ao_float64"; }),
                         "rays", false, true);
        md << "### t_m: exact, clustered ε, auto presets\n\nRelative error; the float64 reference's own cost is in "
              "the notes of the first row of each material (wall = CPU).\n\n";
        for (const auto& c : distinct(
                 rows, [&](const Row& r) { return r.mesh == m && is_tm(r) ? split_method(r.method).second : ""; })) {
            md << "**" << c << "**";
            for (const Row& r : rows)
                if (r.mesh == m && r.knob == "tm_reference" && split_method(r.method).second == c)
                    md << " (float64 reference: " << ms(r.wall_ms) << " on " << r.value << " vertices)";
            md << "\n\n"
               << rows_table(
                      rows, front,
                      select(
                          rows,
                          [&](const Row& r) { return r.mesh == m && is_tm(r) && split_method(r.method).second == c; }),
                      "value", true, true);
        }
        md << "### Presets end to end (own AO + t_m)\n\n"
           << rows_table(rows, front, select(rows, [&](const Row& r) { return r.mesh == m && r.knob == "quality"; }),
                         "preset", true, true);
        md << "### Final image (t_m shading, 8-bit sRGB levels per covered pixel)\n\n"
           << rows_table(
                  rows, front,
                  select(rows,
                         [&](const Row& r) { return r.mesh == m && (r.knob == "image" || r.knob == "image_lut"); }),
                  "preset / LUT", false, true);
        md << "### Deformation: refit, rebuild, amortised re-bakes\n\nA twist played at 15 frames per second; every "
              "frame against a from-scratch bake of the same deformed mesh (rebuild: new BVH and cluster tree). GPU = "
              "bake per frame (refits, AO, t_m); RMS = mean over frames of the per-frame RMS; max over all frames. "
              "Amortised 1/N re-traces 1/N of the AO rays and re-evaluates 1/N of the vertices' t_m per frame "
              "(`jade::Amortisation`); its first frame (a full re-bake) is left out. Plot: deform.png.\n\nAO, absolute "
              "error:\n\n"
           << rows_table(rows, front, select(rows, [&](const Row& r) { return r.mesh == m && r.knob == "deform_ao"; }),
                         "mode", false, true)
           << "t_m, relative error:\n\n"
           << rows_table(rows, front, select(rows, [&](const Row& r) { return r.mesh == m && r.knob == "deform_tm"; }),
                         "mode", true, true);
    }
    md << "## Translucency LUT size\n\n(N + 1) × N texels against `lut_reference` (float64), absolute error of f; "
          "wall = GPU build + read-back. The last row is the renderer's default size.\n\n"
       << rows_table(rows, front, select(rows, [](const Row& r) { return r.knob == "lut_size"; }), "W×H", false, true);
    return md.str();
}

}  // namespace jade::cli::report
