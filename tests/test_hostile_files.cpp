// Hostile files and paths: nothing a glTF, a symbolic link, a planted temporary file or an
// output path does may make Jade read outside the asset's folder or write anywhere but the named
// output (docs/robustness.md, "What Jade promises"). The reader tests need no GPU; the CLI tests
// that bake use a tiny asset.
#include "test_support.hpp"

#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using jade::test::data;
using jade::test::error_of;
using jade::test::run_cli;

constexpr int kError = 1;  // main.cpp: jade::Error

std::string read_all(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// BoxTextured with an external buffer and image, copied into `dir`, its JSON with the image's
/// and the buffer's URIs replaced.
fs::path box(const fs::path& dir, const std::string& image_uri, const std::string& buffer_uri)
{
    const fs::path src = data("gltf_samples/BoxTextured_external");
    fs::create_directories(dir);
    fs::copy_file(src / "BoxTextured0.bin", dir / "BoxTextured0.bin", fs::copy_options::overwrite_existing);
    fs::copy_file(src / "CesiumLogoFlat.png", dir / "CesiumLogoFlat.png", fs::copy_options::overwrite_existing);
    std::string json = read_all(src / "BoxTextured.gltf");
    for (auto [from, to] : {std::pair<std::string, std::string>{"\"CesiumLogoFlat.png\"", '"' + image_uri + '"'},
                            {"\"BoxTextured0.bin\"", '"' + buffer_uri + '"'}})
        json.replace(json.find(from), from.size(), to);
    write(dir / "box.gltf", json);
    return dir / "box.gltf";
}

/// A folder outside the asset's, with a PNG and a buffer in it: what a link may lead to.
fs::path outside_folder(const fs::path& root)
{
    const fs::path out = root / "elsewhere";
    box(out, "CesiumLogoFlat.png", "BoxTextured0.bin");
    write(out / "secret.txt", "not for sharing\n");
    return out;
}

// ------------------------------------------------------------ links out of the folder --

TEST(hostile_links, ALinkToAFileOutsideTheFolderIsRefusedNamingTheUri)
{
    const fs::path root = jade::test::test_folder("hostile");
    const fs::path elsewhere = outside_folder(root);
    const fs::path asset = box(root / "asset", "logo.png", "buffer.bin");
    fs::create_symlink(elsewhere / "CesiumLogoFlat.png", root / "asset" / "logo.png");
    fs::create_symlink(elsewhere / "BoxTextured0.bin", root / "asset" / "buffer.bin");
    const std::string e = error_of([&] { jade::load_mesh(asset); });
    EXPECT_NE(e.find("box.gltf: buffer 0: URI 'buffer.bin' resolves to '"), std::string::npos) << e;
    EXPECT_NE(e.find("outside the glTF file's folder"), std::string::npos) << e;
    EXPECT_NE(e.find("--allow-outside-links"), std::string::npos) << e;

    // Only the image leads out: refused too (an image is embedded in a baked asset).
    fs::remove(root / "asset" / "buffer.bin");
    fs::copy_file(elsewhere / "BoxTextured0.bin", root / "asset" / "buffer.bin");
    const std::string image = error_of([&] { jade::GltfAsset::load(asset); });
    EXPECT_NE(image.find("box.gltf: image 0: URI 'logo.png' resolves to '" + fs::canonical(elsewhere).string() +
                         "/CesiumLogoFlat.png', outside the glTF file's folder"),
              std::string::npos)
        << image;
    for (const auto& load :
         std::vector<std::function<void()>>{[&] { jade::load_scene(asset); }, [&] { jade::load_animated_gltf(asset); }})
        EXPECT_NE(error_of(load).find("resolves to"), std::string::npos) << error_of(load);

    // Allowed on request, and then GltfAsset::files names what was read, links resolved.
    jade::ReadOptions allow;
    allow.allow_outside_links = true;
    const jade::GltfAsset a = jade::GltfAsset::load(asset, nullptr, allow);
    ASSERT_EQ(jade::dev::asset_files(a).size(), 3u);
    EXPECT_EQ(jade::dev::asset_files(a)[0], asset);
    EXPECT_TRUE(fs::equivalent(jade::dev::asset_files(a)[2], elsewhere / "CesiumLogoFlat.png"));
    EXPECT_NO_THROW(jade::load_mesh(asset, allow));
}

TEST(hostile_links, ALinkedFolderThatLeadsOutsideIsRefused)
{
    const fs::path root = jade::test::test_folder("hostile");
    const fs::path elsewhere = outside_folder(root);
    const fs::path asset = box(root / "asset", "textures/CesiumLogoFlat.png", "data/BoxTextured0.bin");
    fs::create_directory_symlink(elsewhere, root / "asset" / "textures");
    fs::create_directory_symlink(elsewhere, root / "asset" / "data");
    EXPECT_NE(error_of([&] { jade::load_mesh(asset); }).find("URI 'data/BoxTextured0.bin' resolves to"),
              std::string::npos);
    // A non-image file behind a link (what an attacker wants) is refused before it is read.
    const fs::path passwd = box(root / "asset2", "textures/secret.txt", "BoxTextured0.bin");
    fs::create_directory_symlink(elsewhere, root / "asset2" / "textures");
    const std::string e = error_of([&] { jade::GltfAsset::load(passwd); });
    EXPECT_NE(e.find("image 0: URI 'textures/secret.txt' resolves to"), std::string::npos) << e;
}

TEST(hostile_links, LinksThatStayInsideTheFolderAreFollowed)
{
    const fs::path root = jade::test::test_folder("hostile");
    const fs::path asset = box(root / "asset", "img/logo.png", "bin/buffer.bin");
    fs::create_directories(root / "asset" / "real");
    fs::rename(root / "asset" / "BoxTextured0.bin", root / "asset" / "real" / "b.bin");
    fs::create_symlink("b.bin", root / "asset" / "real" / "buffer.bin");  // a file link inside
    fs::create_directory_symlink("real", root / "asset" / "bin");         // a linked folder inside
    fs::create_directories(root / "asset" / "img");
    fs::create_symlink("../CesiumLogoFlat.png", root / "asset" / "img" / "logo.png");
    EXPECT_NO_THROW(jade::GltfAsset::load(asset));
    EXPECT_NO_THROW(jade::load_mesh(asset));

    // The asset's own folder reached through a link: judged by real paths on both sides.
    fs::create_directory_symlink(root / "asset", root / "alias");
    EXPECT_NO_THROW(jade::load_mesh(root / "alias" / "box.gltf"));
}

TEST(hostile_links, TheCliRefusesALinkOutUnlessAllowed)
{
    const fs::path root = jade::test::test_folder("hostile");
    const fs::path elsewhere = outside_folder(root);
    const fs::path asset = box(root / "asset", "logo.png", "BoxTextured0.bin");
    fs::create_symlink(elsewhere / "CesiumLogoFlat.png", root / "asset" / "logo.png");
    const fs::path out = root / "asset" / "baked.glb";
    for (const std::string command : {"info", "bake"}) {
        std::vector<std::string> args = {command, asset.string()};
        if (command == "bake") args.insert(args.end(), {"--out", out.string(), "--quality", "draft"});
        const auto r = run_cli(args);
        EXPECT_EQ(r.exit_code, kError) << r.output;
        EXPECT_NE(r.output.find("image 0: URI 'logo.png' resolves to"), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(out));
    const auto r = run_cli({"bake", asset.string(), "--out", out.string(), "--quality", "draft", "--ao-rays", "4",
                            "--allow-outside-links"});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out));
}

// ------------------------------------------------------------------ the atomic writer --

TEST(hostile_writes, APlantedLinkAtTheTemporaryNameIsNeverFollowed)
{
    const fs::path dir = jade::test::test_folder("hostile");
    fs::create_directories(dir);
    const fs::path victim = dir / "victim.txt", target = dir / "out.glb";
    write(victim, "precious\n");
    // The name the writer used to take, and names of the new form: links to the victim.
    fs::create_symlink(victim, dir / ("out.glb.tmp-" + std::to_string(::getpid())));
    fs::create_symlink(victim, dir / ("out.glb.tmp-" + std::to_string(::getpid()) + "-000000000000"));
    jade::dev::write_file_atomically(target, "new bytes");
    EXPECT_EQ(read_all(victim), "precious\n");
    EXPECT_EQ(read_all(target), "new bytes");
    EXPECT_TRUE(fs::is_symlink(dir / ("out.glb.tmp-" + std::to_string(::getpid()))));

    // A link at the output itself is replaced by the file; what it pointed to is left alone.
    fs::remove(target);
    fs::create_symlink(victim, target);
    jade::dev::write_file_atomically(target, "replaced");
    EXPECT_FALSE(fs::is_symlink(target));
    EXPECT_EQ(read_all(target), "replaced");
    EXPECT_EQ(read_all(victim), "precious\n");

    // Likewise through the CLI, whose output check creates a probe file first.
    const auto r = run_cli(
        {"bake", data("tetra_normals.off").string(), "--out", target.string(), "--quality", "draft", "--ao-rays", "4"});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read_all(victim), "precious\n");
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name.find(".tmp-") != std::string::npos) EXPECT_TRUE(fs::is_symlink(e.symlink_status())) << name;
    }
}

TEST(hostile_writes, ReplacingAFileKeepsItsMode)
{
    const fs::path dir = jade::test::test_folder("hostile");
    fs::create_directories(dir);
    const fs::path file = dir / "private.bin";
    write(file, "old");
    ASSERT_EQ(::chmod(file.c_str(), 0600), 0);
    jade::dev::write_file_atomically(file, "new");
    struct stat st {};
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);
    ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
    jade::dev::write_file_atomically(file, "newer");
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0640u);

    // jade bake --in-place: the baked asset keeps the original's mode.
    const fs::path asset = dir / "cube.glb";
    fs::copy_file(data("cube_seams.glb"), asset);
    ASSERT_EQ(::chmod(asset.c_str(), 0600), 0);
    const auto r = run_cli({"bake", asset.string(), "--in-place", "--quality", "draft", "--ao-rays", "4"});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    ASSERT_EQ(::stat(asset.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);
    EXPECT_NE(read_all(asset), read_all(data("cube_seams.glb")));
}

// ------------------------------------------------------------------------ output paths --

TEST(hostile_outputs, AnOutputThatIsAFileTheInputReadsIsRefused)
{
    const fs::path root = jade::test::test_folder("hostile");
    // A buffer and an image with glTF names, so that --out's extension check lets them through.
    const fs::path asset = box(root / "asset", "image.gltf", "buffer.glb");
    fs::rename(root / "asset" / "BoxTextured0.bin", root / "asset" / "buffer.glb");
    fs::rename(root / "asset" / "CesiumLogoFlat.png", root / "asset" / "image.gltf");
    fs::create_symlink("buffer.glb", root / "asset" / "alias.glb");
    fs::create_hard_link(root / "asset" / "image.gltf", root / "asset" / "hard.gltf");
    const std::string buffer = read_all(root / "asset" / "buffer.glb");
    for (const std::string out : {"buffer.glb", "./sub/../buffer.glb", "alias.glb", "image.gltf", "hard.gltf"}) {
        fs::create_directories(root / "asset" / "sub");
        const std::string path = (root / "asset" / out).string();
        const auto r = run_cli({"bake", asset.string(), "--out", path, "--quality", "draft"});
        EXPECT_EQ(r.exit_code, kError) << out << ": " << r.output;
        EXPECT_NE(r.output.find("--out " + path + ": is "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("a file that box.gltf reads"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("baking"), std::string::npos) << r.output;
    }
    EXPECT_EQ(read_all(root / "asset" / "buffer.glb"), buffer);
    EXPECT_NO_THROW(jade::load_mesh(asset));

    // The input itself under another name, without --in-place: refused as before.
    fs::create_symlink("box.gltf", root / "asset" / "same.gltf");
    const auto r = run_cli({"bake", asset.string(), "--out", (root / "asset" / "same.gltf").string()});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("is the input file"), std::string::npos) << r.output;
}

TEST(hostile_outputs, MissingInputsAndFilesInTheWayAreCleanErrors)
{
    const fs::path dir = jade::test::test_folder("hostile");
    fs::create_directories(dir);
    fs::create_symlink(dir / "nowhere.glb", dir / "dangling.glb");
    write(dir / "a_file", "x");
    struct Case {
        std::vector<std::string> args;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {{"bake", (dir / "missing.glb").string(), "--in-place"}, "missing.glb: cannot open: file not found"},
        {{"bake", (dir / "dangling.glb").string(), "--in-place"},
         "dangling.glb: cannot open: a symbolic link to a file that does not exist"},
        {{"bake", (dir / "missing.glb").string(), "--out", (dir / "o.glb").string()}, "missing.glb"},
        {{"deform", data("tetra_normals.off").string(), "--frames", "1", "--out", (dir / "a_file").string()},
         "--out " + (dir / "a_file").string() + ": cannot create the folder"},
    };
    for (const auto& c : cases) {
        const auto r = run_cli(c.args);
        EXPECT_EQ(r.exit_code, kError) << c.args[1] << ": " << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
    }
    EXPECT_EQ(read_all(dir / "a_file"), "x");
}

TEST(hostile_outputs, AnInputWhoseImageFieldsHaveTheWrongTypeIsBlamedNotTheOutput)
{
    // The writer reads the input's own image entries back; a number where the schema has a
    // string is the input's fault, named before anything is baked.
    const fs::path dir = jade::test::test_folder("hostile");
    const fs::path gltf = box(dir, "CesiumLogoFlat.png", "BoxTextured0.bin");
    std::string json = read_all(gltf);
    const std::string uri = "\"uri\"";
    const size_t at = json.find(uri, json.find("\"images\""));
    ASSERT_NE(at, std::string::npos);
    json.insert(at, "\"mimeType\": 5, ");
    write(gltf, json);
    const auto r = run_cli({"bake", gltf.string(), "--quality", "draft", "--out", (dir / "out.glb").string()});
    EXPECT_EQ(r.exit_code, kError) << r.output;
    EXPECT_NE(r.output.find("box.gltf: image 0: mimeType is not a string"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out.glb"));

    // What the schema calls invalid is refused naming the element, not written back.
    const std::string good = read_all(box(dir, "CesiumLogoFlat.png", "BoxTextured0.bin"));
    struct Case {
        std::string from, to, expected;
    };
    for (const Case& c : std::vector<Case>{
             {"\"mesh\"", "\"mesh\": 2147483648, \"x_mesh\"", "node 1: mesh 2147483648 is not an index into meshes"},
             {"\"mesh\"", "\"skin\": 3, \"mesh\"", "node 1: skin 3 is not an index into skins"},
             {"\"mode\"", "\"mode\": -5, \"x_mode\"", "mesh 0 primitive 0: mode -5 is not 0 to 6"},
             {"\"2.0\"", "\"3.0\"", "asset.version is not \"2.x\""}}) {
        std::string json = good;
        const size_t at = json.find(c.from);
        ASSERT_NE(at, std::string::npos) << c.from;
        json.replace(at, c.from.size(), c.to);
        write(gltf, json);
        const auto bad = run_cli({"bake", gltf.string(), "--quality", "draft", "--out", (dir / "out.glb").string()});
        EXPECT_EQ(bad.exit_code, kError) << bad.output;
        EXPECT_NE(bad.output.find("box.gltf: " + c.expected), std::string::npos) << c.expected << ": " << bad.output;
        EXPECT_FALSE(fs::exists(dir / "out.glb"));
    }
}

}  // namespace
