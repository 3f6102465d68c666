// args.hpp - a small, strict command-line parser for the jade sample: every option is declared
// with its help text, unknown options and missing values are errors that name the flag.
#pragma once

#include <jade/error.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace jade::cli {

struct OptionSpec {
    std::string name;        ///< without the leading "--"
    std::string value_name;  ///< empty for a flag without value
    std::string help;
};

class Args {
public:
    /// Parses argv[first..]; options may come before or after positionals, "--x=v" or "--x v".
    Args(std::string command, std::vector<OptionSpec> specs, int argc, char** argv, int first);

    const std::vector<std::string>& positional() const { return positional_; }
    bool flag(const std::string& name) const { return values_.count(name) > 0; }
    std::optional<std::string> get(const std::string& name) const;  ///< the last value given
    /// Every value of a repeatable option, in command-line order (empty when not given).
    std::vector<std::string> all(const std::string& name) const;
    std::string get_or(const std::string& name, const std::string& fallback) const;
    double number(const std::string& name, double fallback, double lo, double hi) const;
    uint32_t count(const std::string& name, uint32_t fallback, uint32_t lo, uint32_t hi) const;
    /// "x,y,z" → three numbers.
    std::optional<std::array<double, 3>> vec3(const std::string& name) const;
    /// "WxH" → two whole numbers in [1, max], or `fallback`'s.
    std::pair<uint32_t, uint32_t> size(const std::string& name, const std::string& fallback, uint32_t max) const;
    /// Exactly three finite comma-separated numbers ("1,2,3"; not "1,2,3," nor "1,,3"), or none.
    static std::optional<std::array<double, 3>> triple(const std::string& text);
    std::string help() const;
    [[noreturn]] void fail(const std::string& message) const;

private:
    std::string command_;
    std::vector<OptionSpec> specs_;
    std::vector<std::string> positional_;
    std::map<std::string, std::string> values_;
    std::map<std::string, std::vector<std::string>> all_values_;
};

/// Raised for a wrong command line: the message goes with a hint to --help; exit code 2.
class UsageError : public Error {
public:
    using Error::Error;
};

}  // namespace jade::cli
