// Bad input through the command line: every malformed file in tests/data/bad must make
// `jade info` and `jade bake` fail cleanly (exit code 1, an error naming the file, no output
// and no temporary file left behind), and every malformed command line must be a usage error
// (exit code 2, a message naming the flag). Never a crash: an exit code of 128 or more is a
// signal (test_support.cpp maps it so), and sanitizer reports in the output are failures too.
// No test here touches the GPU: output paths are checked before the mesh is loaded.
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using jade::test::data;
using jade::test::out;
using jade::test::run_cli;

constexpr int kError = 1;  // main.cpp: jade::Error
constexpr int kUsage = 2;  // main.cpp: jade::cli::UsageError

/// A valid mesh that loads in microseconds, for the flag tests (mesh flags are checked after
/// the mesh is loaded, so the mesh must be good for the flag error to be the one reported).
fs::path tiny_mesh() { return data("tetra_normals.off"); }

std::string describe(const std::vector<std::string>& args, const jade::test::CliResult& r)
{
    std::string cmd = "jade";
    for (const auto& a : args) cmd += " " + a;
    return cmd + "\n  exit code " + std::to_string(r.exit_code) + "\n  output: " + r.output;
}

/// Signs that the process died or a sanitizer complained, whatever the exit code says.
void expect_no_crash(const std::vector<std::string>& args, const jade::test::CliResult& r)
{
    EXPECT_GE(r.exit_code, 0) << "could not run: " << describe(args, r);
    EXPECT_LT(r.exit_code, 128) << "killed by signal " << r.exit_code - 128 << ": " << describe(args, r);
    for (const char* marker :
         {"Sanitizer", "runtime error:", "internal error", "terminate called", "Segmentation fault"})
        EXPECT_EQ(r.output.find(marker), std::string::npos) << "'" << marker << "' in output: " << describe(args, r);
}

/// Entries of `folder` whose name contains ".tmp-" (write_atomically's temporary files).
std::vector<std::string> temporaries(const fs::path& folder)
{
    std::vector<std::string> found;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder, ec))
        if (e.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(e.path().string());
    return found;
}

std::vector<fs::path> bad_files()
{
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(data("bad")))
        if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

// ------------------------------------------------------------------------ malformed files --

TEST(cli_bad_input, InfoFailsCleanlyOnEveryMalformedFile)
{
    const auto files = bad_files();
    ASSERT_GE(files.size(), 60u) << "tests/data/bad looks incomplete";
    for (const auto& path : files) {
        const std::vector<std::string> args = {"info", path.string()};
        const auto r = run_cli(args);
        expect_no_crash(args, r);
        EXPECT_EQ(r.exit_code, kError) << describe(args, r);
        EXPECT_NE(r.output.find("jade info: error: "), std::string::npos) << describe(args, r);
        EXPECT_NE(r.output.find(path.filename().string()), std::string::npos)
            << "the file is not named: " << describe(args, r);
    }
}

TEST(cli_bad_input, BakeFailsCleanlyOnEveryMalformedFileAndWritesNothing)
{
    for (const auto& path : bad_files()) {
        const auto output = out("cli_bad_input/bake/" + path.filename().string() + ".glb");
        const std::vector<std::string> args = {"bake", path.string(), "--out", output.string(), "--quality", "draft"};
        const auto r = run_cli(args);
        expect_no_crash(args, r);
        EXPECT_EQ(r.exit_code, kError) << describe(args, r);
        EXPECT_NE(r.output.find("jade bake: error: "), std::string::npos) << describe(args, r);
        EXPECT_NE(r.output.find(path.filename().string()), std::string::npos)
            << "the file is not named: " << describe(args, r);
        EXPECT_FALSE(fs::exists(output)) << "output written: " << describe(args, r);
        EXPECT_EQ(temporaries(output.parent_path()), std::vector<std::string>{}) << describe(args, r);
    }
}

TEST(cli_bad_input, MissingFilesAndFoldersAreErrorsNamingThem)
{
    const auto folder = out("cli_bad_input/folder.off/x").parent_path();
    fs::create_directories(folder);
    const auto output = out("cli_bad_input/missing.glb");
    for (const auto& path : {data("no_such_mesh.off"), folder}) {
        for (const auto& args : {std::vector<std::string>{"info", path.string()},
                                 std::vector<std::string>{"bake", path.string(), "--out", output.string()}}) {
            const auto r = run_cli(args);
            expect_no_crash(args, r);
            EXPECT_EQ(r.exit_code, kError) << describe(args, r);
            EXPECT_NE(r.output.find(path.filename().string()), std::string::npos) << describe(args, r);
        }
    }
    EXPECT_FALSE(fs::exists(output));
}

// ----------------------------------------------------------------------- bad command lines --

struct BadCommandLine {
    std::vector<std::string> args;  ///< "MESH" and "OUT" are replaced by a tiny mesh and an output path
    std::string expected;           ///< a phrase of the message, naming the flag
};

/// Test names and failure messages show the command line ("jade bake MESH --out OUT --d 0").
void PrintTo(const BadCommandLine& c, std::ostream* os)
{
    *os << "jade";
    for (const auto& a : c.args) *os << " " << a;
}

class cli_bad_flags : public ::testing::TestWithParam<BadCommandLine> {};

TEST_P(cli_bad_flags, AreUsageErrorsNamingTheFlag)
{
    // One folder per case: ctest runs the cases in parallel, and each folder must stay empty.
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string id = std::string(test->test_suite_name()) + "." + test->name();
    std::replace(id.begin(), id.end(), '/', '_');
    const auto output = out("cli_bad_input/flags/" + id + "/out.glb");
    std::vector<std::string> args = GetParam().args;
    for (auto& a : args) {
        if (a == "MESH") a = tiny_mesh().string();
        if (a == "OUT") a = output.string();
        if (a == "PNG") a = (output.parent_path() / "out.png").string();
    }
    const auto r = run_cli(args);
    expect_no_crash(args, r);
    EXPECT_EQ(r.exit_code, kUsage) << describe(args, r);
    EXPECT_NE(r.output.find(GetParam().expected), std::string::npos)
        << "expected '" << GetParam().expected << "': " << describe(args, r);
    EXPECT_FALSE(fs::exists(output)) << describe(args, r);
    EXPECT_FALSE(fs::exists(output.parent_path() / "out.png")) << describe(args, r);
    EXPECT_EQ(temporaries(output.parent_path()), std::vector<std::string>{}) << describe(args, r);
}

INSTANTIATE_TEST_SUITE_P(
    Bake, cli_bad_flags,
    ::testing::Values(
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--bogus"}, "unknown option --bogus"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--bogus=3"}, "unknown option --bogus"},
        BadCommandLine{{"bake", "MESH", "--out"}, "option --out needs a value"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays"}, "option --ao-rays needs a value"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--validation=1"}, "option --validation takes no value"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays", "0"}, "--ao-rays: 0 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays", "abc"}, "--ao-rays: 'abc' is not a number"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays", "1e9"}, "--ao-rays: 1e+09 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays", "2.5"}, "--ao-rays: expected a whole number"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays", "nan"}, "--ao-rays: 'nan' is not a number"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-rays="}, "--ao-rays: '' is not a number"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--seed", "-1"}, "--seed: -1 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--quality", "ultra"}, "--quality: 'ultra' is not one of"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--method", "x"}, "--method: 'x' is not one of"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--epsilon", "-1"}, "--epsilon: -1 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--epsilon", "inf"}, "--epsilon: 'inf' is not a number"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--ao-distance", "0"}, "--ao-distance: 0 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--d", "0"}, "--d: 0 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--mm-per-unit", "-2"}, "--mm-per-unit: -2 is out of range"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--strength", "x1"}, "--strength: 'x1' is not a number"},
        BadCommandLine{{"bake", "MESH", "--out", "OUT", "--material", "unobtainium"}, "--material: "},
        BadCommandLine{{"bake", "MESH"}, "--out FILE is required"},
        BadCommandLine{{"bake", "--out", "OUT"}, "expects exactly one MESH"},
        BadCommandLine{{"bake", "MESH", "MESH", "--out", "OUT"}, "expects exactly one MESH"},
        BadCommandLine{{"bake"}, "expects exactly one MESH"}),
    [](const auto& info) { return "case" + std::to_string(info.index); });

// Numbers and lists are parsed whole: no wrap-around, no trailing or doubled separator, and the
// camera's degenerate cases named as what they are.
INSTANTIATE_TEST_SUITE_P(
    Render, cli_bad_flags,
    ::testing::Values(
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--size", "4294967360x64"}, "--size: expected WxH"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--size", "64x64x"}, "--size: expected WxH"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--size", "0x64"}, "--size: expected WxH"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--light", "dir:0,0,1:1,1,1,"}, "--light: expected dir:"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--light", "dir:0,0,1:1,1,1:"}, "--light: expected dir:"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--light", "dir:0,,1:1,1,1"}, "--light: expected dir:"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--eye", "0,0,5,"}, "--eye: expected x,y,z"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--eye", "1,2,3", "--target", "1,2,3"},
                       "--eye equals --target"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--up", "0,0,0"}, "--up: the up vector is zero"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--eye", "0,5,0", "--target", "0,0,0", "--up", "0,1,0"},
                       "--up is parallel to the view direction"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--medium", "1,1,1,:1,1,1"}, "sigma_s '1,1,1,' is not three"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--medium", "1,1,1:1,1,1:"}, "--medium 1,1,1:1,1,1:: need"},
        BadCommandLine{{"render", "MESH", "--out", "PNG", "--medium", "1,1,1:1,1,1", "--ior", "0.2"},
                       "--ior: 0.2 is out of range (0.2, 5)"},
        BadCommandLine{{"deform", "MESH", "--out", "OUT", "--size", "18446744073709551680x8"}, "--size: expected WxH"}),
    [](const auto& info) { return "case" + std::to_string(info.index); });

INSTANTIATE_TEST_SUITE_P(
    Info, cli_bad_flags,
    ::testing::Values(BadCommandLine{{"info", "MESH", "--ao-rays", "4"}, "unknown option --ao-rays"},
                      BadCommandLine{{"info", "--device"}, "option --device needs a value"},
                      BadCommandLine{{"info", "--materials=yes"}, "option --materials takes no value"},
                      BadCommandLine{{"info", "MESH", "MESH"}, "takes at most one mesh"}),
    [](const auto& info) { return "case" + std::to_string(info.index); });

INSTANTIATE_TEST_SUITE_P(Main, cli_bad_flags,
                         ::testing::Values(BadCommandLine{{}, "usage: jade COMMAND"},
                                           BadCommandLine{{"frobnicate", "MESH"}, "unknown command 'frobnicate'"}),
                         [](const auto& info) { return "case" + std::to_string(info.index); });

// ------------------------------------------------------------- bad output paths, early --

struct BadOutput {
    std::vector<std::string> args;  ///< "MESH" is replaced by a tiny mesh, "DIR/" by a fresh folder
    int exit_code;
    std::string expected;  ///< a phrase of the message, naming the flag and the path
};

TEST(cli_bad_input, BadOutputPathsFailBeforeAnyWork)
{
    // An output that cannot be written is found before the mesh is loaded and before the GPU is
    // touched: no "baking" line, exit 2 for a wrong extension (a usage error), exit 1 for a
    // folder that is missing, not a folder, or where no file can be created; nothing is left.
    const auto dir = out("cli_bad_input/outputs/x").parent_path();
    fs::remove_all(dir);
    fs::create_directories(dir / "a_folder.glb");
    std::ofstream(dir / "a_file.txt") << "not a folder\n";
    const std::vector<BadOutput> cases = {
        {{"bake", "MESH", "--out", "DIR/x.stl"},
         kUsage,
         "--out DIR/x.stl: unsupported extension '.stl' (supported: .glb, .gltf)"},
        {{"bake", "MESH", "--out", "DIR/x"}, kUsage, "--out DIR/x: unsupported extension ''"},
        {{"bake", "MESH", "--out", "DIR/x.png"}, kUsage, "unsupported extension '.png' (supported: .glb, .gltf)"},
        {{"bake", "MESH", "--out", "DIR/missing/x.glb"},
         kError,
         "--out DIR/missing/x.glb: folder 'DIR/missing' does not exist"},
        {{"bake", "MESH", "--out", "DIR/a_folder.glb"}, kError, "--out DIR/a_folder.glb: is a folder, not a file"},
        {{"bake", "MESH", "--out", "DIR/a_file.txt/x.glb"}, kError, "'DIR/a_file.txt' is not a folder"},
        // Root ignores permission bits; /proc refuses new files to everyone.
        {{"bake", "MESH", "--out", "/proc/jade-test.glb"},
         kError,
         "--out /proc/jade-test.glb: cannot create a file in folder '/proc'"},
        {{"render", "MESH", "--out", "DIR/x.jpg"},
         kUsage,
         "--out DIR/x.jpg: unsupported extension '.jpg' (supported: .png, .exr)"},
        {{"render", "MESH", "--out", "DIR/missing/x.png"}, kError, "folder 'DIR/missing' does not exist"},
        {{"figure1", "--mesh", "MESH", "--out", "DIR/x.tga"}, kUsage, "--out DIR/x.tga: unsupported extension '.tga'"},
        {{"figure1", "--mesh", "MESH", "--out", "/proc/f.png"}, kError, "cannot create a file in folder '/proc'"},
        {{"report", "MESH", "--tiny", "--out", "DIR/a_file.txt"},
         kError,
         "--out DIR/a_file.txt: cannot create the folder"},
        {{"report", "MESH", "--tiny", "--out", "/proc/jade-report"},
         kError,
         "--out /proc/jade-report: cannot create the folder"},
    };
    const auto substitute = [&](std::string s) {
        if (s == "MESH") return tiny_mesh().string();
        if (s.rfind("DIR/", 0) == 0) return (dir / s.substr(4)).string();
        for (size_t at; (at = s.find("DIR/")) != std::string::npos;) s.replace(at, 4, dir.string() + "/");
        return s;
    };
    for (const auto& c : cases) {
        std::vector<std::string> args;
        for (const auto& a : c.args) args.push_back(substitute(a));
        const auto r = run_cli(args);
        expect_no_crash(args, r);
        EXPECT_EQ(r.exit_code, c.exit_code) << describe(args, r);
        EXPECT_NE(r.output.find(substitute(c.expected)), std::string::npos)
            << "expected '" << c.expected << "': " << describe(args, r);
        EXPECT_EQ(r.output.find("baking"), std::string::npos) << "the bake ran: " << describe(args, r);
    }
    // Nothing created: only the two entries made above, no temporary or probe file anywhere.
    std::vector<std::string> left;
    for (const auto& e : fs::recursive_directory_iterator(dir)) left.push_back(fs::relative(e.path(), dir).string());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"a_file.txt", "a_folder.glb"}));
    EXPECT_EQ(temporaries("/proc"), std::vector<std::string>{});
}

}  // namespace
