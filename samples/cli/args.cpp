#include "args.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string_view>

namespace jade::cli {

Args::Args(std::string command, std::vector<OptionSpec> specs, int argc, char** argv, int first)
    : command_(std::move(command)), specs_(std::move(specs))
{
    specs_.push_back({"help", "", "show this help"});
    for (int i = first; i < argc; ++i) {
        std::string a = argv[i];
        if (a.rfind("--", 0) != 0 || a == "--") {
            positional_.push_back(a);
            continue;
        }
        std::string name = a.substr(2), value;
        bool inline_value = false;
        if (auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
            inline_value = true;
        }
        const OptionSpec* spec = nullptr;
        for (const auto& s : specs_)
            if (s.name == name) spec = &s;
        if (!spec) fail("unknown option --" + name);
        if (spec->value_name.empty()) {
            if (inline_value) fail("option --" + name + " takes no value");
        } else if (!inline_value) {
            if (i + 1 >= argc) fail("option --" + name + " needs a value (" + spec->value_name + ")");
            value = argv[++i];
        }
        values_[name] = value;
        all_values_[name].push_back(value);
    }
}

void Args::fail(const std::string& message) const { throw UsageError("jade " + command_ + ": " + message); }

std::optional<std::string> Args::get(const std::string& name) const
{
    auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second;
}

std::vector<std::string> Args::all(const std::string& name) const
{
    auto it = all_values_.find(name);
    return it == all_values_.end() ? std::vector<std::string>{} : it->second;
}

std::string Args::get_or(const std::string& name, const std::string& fallback) const
{
    return get(name).value_or(fallback);
}

static bool parse_double(const std::string& s, double& out)
{
    if (s.empty()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}

double Args::number(const std::string& name, double fallback, double lo, double hi) const
{
    auto v = get(name);
    if (!v) return fallback;
    double x;
    if (!parse_double(*v, x)) fail("--" + name + ": '" + *v + "' is not a number");
    if (x < lo || x > hi) {
        std::ostringstream os;
        os << "--" << name << ": " << x << " is out of range [" << lo << ", " << hi << "]";
        fail(os.str());
    }
    return x;
}

uint32_t Args::count(const std::string& name, uint32_t fallback, uint32_t lo, uint32_t hi) const
{
    double x = number(name, fallback, lo, hi);
    if (x != std::floor(x)) fail("--" + name + ": expected a whole number");
    return uint32_t(x);
}

std::optional<std::array<double, 3>> Args::triple(const std::string& text)
{
    // Split on every comma, so that an empty part (a trailing or doubled separator) is refused.
    std::array<double, 3> out{};
    size_t begin = 0;
    for (int n = 0; n < 3; ++n) {
        const size_t end = n < 2 ? text.find(',', begin) : text.size();
        if (end == std::string::npos || !parse_double(text.substr(begin, end - begin), out[n])) return std::nullopt;
        begin = end + 1;
    }
    return out;  // the third part runs to the end: "1,2,3," and "1,2,3,4" fail to parse there
}

std::optional<std::array<double, 3>> Args::vec3(const std::string& name) const
{
    auto v = get(name);
    if (!v) return std::nullopt;
    auto out = triple(*v);
    if (!out) fail("--" + name + ": expected x,y,z (three finite numbers), got '" + *v + "'");
    return out;
}

std::pair<uint32_t, uint32_t> Args::size(const std::string& name, const std::string& fallback, uint32_t max) const
{
    const std::string s = get_or(name, fallback);
    // Parsed as 64-bit digits, so that 4294967360 is out of range rather than wrapped to 64.
    auto whole = [&](std::string_view t, uint64_t& out) {
        if (t.empty() || t.size() > 18) return false;
        out = 0;
        for (char c : t) {
            if (c < '0' || c > '9') return false;
            out = out * 10 + uint64_t(c - '0');
        }
        return true;
    };
    const size_t x = s.find('x');
    uint64_t w = 0, h = 0;
    if (x == std::string::npos || !whole(std::string_view(s).substr(0, x), w) ||
        !whole(std::string_view(s).substr(x + 1), h) || w == 0 || h == 0 || w > max || h > max)
        fail("--" + name + ": expected WxH with 1.." + std::to_string(max) + " pixels each, got '" + s + "'");
    return {uint32_t(w), uint32_t(h)};
}

std::string Args::help() const
{
    std::ostringstream os;
    os << "options:\n";
    for (const auto& s : specs_) {
        std::string left = "  --" + s.name + (s.value_name.empty() ? "" : " " + s.value_name);
        os << left << std::string(left.size() < 30 ? 30 - left.size() : 1, ' ') << s.help << "\n";
    }
    return os.str();
}

}  // namespace jade::cli
