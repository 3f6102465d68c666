#include "test_support.hpp"

#include <jade/error.hpp>

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>

namespace jade::test {

// The environment variable, else the build's default (tests/CMakeLists.txt).
static std::filesystem::path env_path(const char* var)
{
    const char* v = std::getenv(var);
    if (v && *v) return v;
    std::string name = var;
    if (name == "JADE_ASSETS") return JADE_DEFAULT_ASSETS;
    if (name == "JADE_TEST_DATA") return JADE_DEFAULT_TEST_DATA;
    if (name == "JADE_TEST_OUT") return JADE_DEFAULT_TEST_OUT;
    if (name == "JADE_CLI") return JADE_DEFAULT_CLI;
    ADD_FAILURE() << var << " is not set";
    return {};
}

std::filesystem::path asset(const std::string& name)
{
    auto p = env_path("JADE_ASSETS") / name;
    if (!std::filesystem::exists(p)) ADD_FAILURE() << p << " is missing: run third_party/fetch_assets.sh";
    return p;
}

std::filesystem::path data(const std::string& name) { return env_path("JADE_TEST_DATA") / name; }

std::filesystem::path out(const std::string& name)
{
    auto p = env_path("JADE_TEST_OUT") / name;
    std::filesystem::create_directories(p.parent_path());
    std::filesystem::remove(p);
    return p;
}

std::filesystem::path test_folder(const std::string& folder)
{
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    const std::filesystem::path dir = out(folder + "/" + test + "/x").parent_path();
    std::filesystem::remove_all(dir);
    return dir;
}

std::string error_of(const std::function<void()>& f)
{
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no jade::Error)";
}

bool closed_and_oriented(const PreparedMesh& m)
{
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) ++edges[{m.indices[t + k], m.indices[t + (k + 1) % 3]}];
    for (const auto& [edge, count] : edges) {
        auto twin = edges.find({edge.second, edge.first});
        if (count != 1 || twin == edges.end() || twin->second != 1) return false;
    }
    return true;
}

std::filesystem::path cli() { return env_path("JADE_CLI"); }

static std::string shell_quote(const std::string& s)
{
    std::string q = "'";
    for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

CliResult run_cli(const std::vector<std::string>& args)
{
    std::string cmd = shell_quote(env_path("JADE_CLI").string());
    for (const auto& a : args) cmd += " " + shell_quote(a);
    return run_shell(cmd);
}

CliResult run_shell(const std::string& command)
{
    const std::string cmd = command + " 2>&1";
    CliResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
    int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

}  // namespace jade::test
