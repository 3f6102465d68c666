// Shared helpers for the test executables: where assets and outputs live, running the CLI,
// errors and mesh checks several tests make.
#pragma once

#include <jade/mesh.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace jade::test {

/// A mesh fetched by third_party/fetch_assets.sh (JADE_ASSETS). Fails the test if missing.
std::filesystem::path asset(const std::string& name);
/// A file under tests/data (JADE_TEST_DATA).
std::filesystem::path data(const std::string& name);
/// A fresh path under the build's test output folder (JADE_TEST_OUT), parent created.
std::filesystem::path out(const std::string& name);
/// An empty folder `folder`/<name of the running test> under the test output folder (its old
/// contents removed, the folder itself left for the test to create).
std::filesystem::path test_folder(const std::string& folder);

/// The message of the jade::Error that `f` throws, or "(no jade::Error)".
std::string error_of(const std::function<void()>& f);
/// Every edge of a closed, consistently oriented surface is used exactly once in each direction.
bool closed_and_oriented(const PreparedMesh& m);

struct CliResult {
    int exit_code = -1;
    std::string output;  ///< stdout and stderr together
};
/// The `jade` command-line sample's executable (JADE_CLI).
std::filesystem::path cli();
/// Runs `command` in the shell: its exit status (128 + the signal if one ended it), stdout and
/// stderr together.
CliResult run_shell(const std::string& command);
/// Runs the `jade` command-line sample with the given arguments (no shell quoting needed).
CliResult run_cli(const std::vector<std::string>& args);

}  // namespace jade::test
