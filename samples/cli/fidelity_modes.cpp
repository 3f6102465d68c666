// fidelity_modes.cpp - see fidelity_modes.hpp.
#include "fidelity_modes.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace jade::cli {

using json = nlohmann::json;

std::vector<const Mode*> modes_from_args(const Args& args)
{
    std::vector<const Mode*> out;
    std::string known;
    for (const Mode& m : kModes) known += (known.empty() ? "" : ", ") + std::string(m.name);
    if (!args.get("modes")) {
        for (const Mode& m : kModes) out.push_back(&m);
        return out;
    }
    std::stringstream list(*args.get("modes"));
    for (std::string word; std::getline(list, word, ',');) {
        const Mode* found = nullptr;
        for (const Mode& m : kModes)
            if (word == m.name) found = &m;
        if (!found) args.fail("--modes: '" + word + "' is not one of " + known);
        if (std::find(out.begin(), out.end(), found) != out.end()) args.fail("--modes: '" + word + "' is listed twice");
        out.push_back(found);
    }
    if (out.empty()) args.fail("--modes: no mode given (known: " + known + ")");
    return out;
}

std::vector<bool> shadow_states(const Args& args)
{
    const std::string v = args.get_or("shadows", args.flag("no-shadows") ? "off" : "on");
    if (v == "on") return {true};
    if (v == "off") return {false};
    if (v == "both") return {true, false};
    args.fail("--shadows: '" + v + "' is not on, off or both");
}

std::string column(const Mode& m, bool shadows) { return std::string(m.name) + (shadows ? "" : "/noshadow"); }

std::string name_for_file(std::string column)
{
    std::replace(column.begin(), column.end(), '/', '_');
    return column;
}

namespace {
/// Luminance (Rec. 709) of a JSON RGB triple.
double luminance(const json& v)
{
    return 0.2126 * v[0].get<double>() + 0.7152 * v[1].get<double>() + 0.0722 * v[2].get<double>();
}
}  // namespace

std::string fidelity_markdown(const json& rows, const std::vector<const Mode*>& modes, const std::vector<bool>& shadows,
                              const std::string& device)
{
    std::ostringstream md;
    char cell[128];
    std::vector<std::string> columns;
    for (const Mode* m : modes)
        for (bool s : shadows) columns.push_back(column(*m, s));
    auto bold = [](const std::string& c, const std::string& text) {
        return c.rfind("default", 0) == 0 ? "**" + text + "**" : text;
    };
    md << "| scene | set";
    for (const auto& c : columns) md << " | " << bold(c, c);
    md << " | GPU ms per mode (" << (shadows[0] ? "shadowed" : "no shadows")
       << ") | thin region, path tracer | thin region, default |\n|---|---";
    for (size_t k = 0; k < columns.size() + 3; ++k) md << "|---";
    md << "|\n";
    // Per group (the light of the committed scenes, front, side, back; the held-out regimes'
    // apart): the sum of masked FLIP per column, the thin region's luminance summed per column
    // and for the path tracer (their ratio: the glow of thin parts under a back light), the count.
    struct Group {
        std::vector<double> flip, thin;
        double thin_reference = 0;
        int count = 0;
    };
    std::map<std::string, Group> groups;
    std::vector<std::string> order;  // committed front, side, back first, then the rest as met
    for (const char* light : {"front", "side", "back"}) order.push_back(light);
    for (const json& r : rows) {
        const std::string light = r["light"];
        const std::string key = r["set"] == "regimes" ? "held out, " + light : light;
        if (std::find(order.begin(), order.end(), key) == order.end()) order.push_back(key);
        Group& g = groups[key];
        g.flip.resize(columns.size()), g.thin.resize(columns.size());
        ++g.count;
        g.thin_reference += luminance(r["thin_reference"]);
        md << "| " << r["scene"].get<std::string>() << " | " << r["set"].get<std::string>();
        std::string ms;
        for (size_t k = 0; k < columns.size(); ++k) {
            const json& c = r[columns[k]];
            g.flip[k] += c["flip_masked"].get<double>();
            g.thin[k] += luminance(c["thin"]);
            std::snprintf(cell, sizeof cell, "%.3f", c["flip_masked"].get<double>());
            md << " | " << bold(columns[k], cell);
            if (k % shadows.size() != 0) continue;  // the first shadow state's times only
            std::snprintf(cell, sizeof cell, "%s%.0f", ms.empty() ? "" : " / ", c["gpu_ms"].get<double>());
            ms += cell;
        }
        auto rgb = [&](const json& v) {
            std::snprintf(cell, sizeof cell, "%.3f %.3f %.3f", v[0].get<double>(), v[1].get<double>(),
                          v[2].get<double>());
            return std::string(cell);
        };
        const bool back = light == "back" && r.contains("default");
        md << " | " << ms << " | " << (back ? rgb(r["thin_reference"]) : "") << " | "
           << (back ? rgb(r["default"]["thin"]) : "") << " |\n";
    }
    auto summary = [&](const char* title, auto value) {
        md << "\n" << title << "\n\n| light | scenes";
        for (const auto& c : columns) md << " | " << bold(c, c);
        md << " |\n|---|---";
        for (size_t k = 0; k < columns.size(); ++k) md << "|---";
        md << "|\n";
        for (const std::string& key : order) {
            if (!groups.count(key)) continue;
            const Group& g = groups.at(key);
            md << "| " << key << " | " << g.count;
            for (size_t k = 0; k < columns.size(); ++k) {
                std::snprintf(cell, sizeof cell, "%.3f", value(g, k));
                md << " | " << bold(columns[k], cell);
            }
            md << " |\n";
        }
    };
    summary("Mean masked LDR FLIP per light (lower is closer to the path tracer; the held-out regimes apart):",
            [](const Group& g, size_t k) { return g.flip[k] / g.count; });
    summary("The thin region's luminance summed over the scenes, over the path tracer's (1 is right; under the back "
            "light it is the glow of thin parts):",
            [](const Group& g, size_t k) { return g.thin[k] / std::max(g.thin_reference, 1e-12); });
    md << "\nModes:";
    for (const Mode* m : modes) md << " `" << m->name << "`: " << m->what << ";";
    md << " `/noshadow`: the same without the mesh's shadows.\nDevice: " << device
       << " (the references' size, 4x MSAA, GPU time of one frame per mode).\n";
    return md.str();
}

}  // namespace jade::cli
