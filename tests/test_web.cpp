// The WebGL2 renderer (web/, docs/web.md) in a real browser: web/test/render_scenes.mjs draws the
// committed baked bunny (blue-jewel) in headless Chromium (WebGL2 on SwiftShader) with
// JadeTranslucentMaterial, front- and back-lit (web/test/scenes.json), and this test compares each
// image with `jade render` of the same file, camera and lights by LDR FLIP (with shadows on both
// sides, and for a second material without). The browser and its npm packages come from
// third_party/build.sh (install_web.sh); where they are missing the test fails under CI=true and
// is skipped elsewhere, saying what to run.
#include "flip.hpp"
#include "gltf_reader.hpp"
#include "test_support.hpp"

#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::filesystem::path web(const std::string& name) { return std::filesystem::path(JADE_WEB_DIR) / name; }

jade::flip::Image load_png(const std::filesystem::path& path)
{
    const jade::dev::LoadedImage img = jade::dev::load_image(path);
    return jade::flip::from_linear(uint32_t(img.width), uint32_t(img.height), img.rgba.data(), 4);
}

// Runs a shell command; its exit status, stdout and stderr together in `output`.
int run(const std::string& command, std::string& output)
{
    const jade::test::CliResult r = jade::test::run_shell(command);
    output += r.output;
    return r.exit_code;
}

nlohmann::json read_json(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path.string() + ": cannot be read");
    return nlohmann::json::parse(in);
}

std::string triple(const nlohmann::json& a)
{
    std::ostringstream s;
    s << a.at(0).get<double>() << ',' << a.at(1).get<double>() << ',' << a.at(2).get<double>();
    return s.str();
}

// What the browser side needs, or why it cannot run.
std::string missing_browser_side()
{
    const char* chromium = std::getenv("JADE_CHROMIUM");
    const std::filesystem::path browser = chromium && *chromium ? chromium : "/usr/bin/chromium-headless-shell";
    if (!std::filesystem::exists(browser))
        return "no headless Chromium at " + browser.string() +
               " (Debian package chromium-headless-shell: bash third_party/install_web.sh)";
    if (!std::filesystem::exists(web("node_modules/three/package.json")) ||
        !std::filesystem::exists(web("node_modules/puppeteer-core/package.json")))
        return "web/node_modules lacks three or puppeteer-core (bash third_party/install_web.sh runs npm ci there)";
    std::string output;
    if (run("node --version", output) != 0) return "no Node.js (node): " + output;
    return "";
}

bool in_ci()
{
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

// The browser's images of `glb` against jade render's, per scene of web/test/scenes.json, into
// `dir`: LDR FLIP within `bound` (per scene), and MeshPhysicalMaterial's FLIP printed. `frames`
// > 0: the page also times JadeTranslucentMaterial against MeshStandardMaterial. `light_path`:
// where both sides read the transmission's path (auto: each picks as Jade's resolve_light_path);
// `shadows`: whether both sides shadow the lights (jade render's default) or neither does.
void compare_with_jade_render(const std::filesystem::path& glb, const std::filesystem::path& dir,
                              const std::map<std::string, double>& bound, int frames, const std::string& light_path,
                              bool shadows)
{
    std::filesystem::create_directories(dir);
    const nlohmann::json config = read_json(web("test/scenes.json"));
    const auto& camera = config.at("camera");
    const std::string size =
        std::to_string(config.at("size").at(0).get<int>()) + "x" + std::to_string(config.at("size").at(1).get<int>());

    // jade render of each scene: the same file, camera and lights; the ALU evaluation of the
    // cosine-Gaussian (the web material's).
    for (const auto& [name, lights] : config.at("scenes").items()) {
        std::vector<std::string> args = {"render",       glb.string(),
                                         "--eye",        triple(camera.at("eye")),
                                         "--target",     triple(camera.at("target")),
                                         "--up",         triple(camera.at("up")),
                                         "--fov",        std::to_string(camera.at("fov").get<double>()),
                                         "--size",       size,
                                         "--eval",       "alu",
                                         "--light-path", light_path,
                                         "--out",        (dir / ("jade_" + name + ".png")).string()};
        if (!shadows) args.push_back("--no-shadows");
        for (const auto& l : lights) {
            const std::string type = l.at("type");
            ASSERT_TRUE(type == "dir" || type == "point") << "scenes.json: light type " << type;
            args.push_back("--light");
            args.push_back(type + ":" + triple(l.at("vector")) + ":" + triple(l.at("color")));
        }
        const auto r = jade::test::run_cli(args);
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }

    std::string output;
    const int rc = run("node '" + web("test/render_scenes.mjs").string() + "' --glb '" + glb.string() + "' --out '" +
                           dir.string() + "' --frames " + std::to_string(frames) + " --light-path " + light_path +
                           (shadows ? "" : " --no-shadows"),
                       output);
    std::printf("%s", output.c_str());
    ASSERT_EQ(rc, 0) << output;

    for (const auto& [name, lights] : config.at("scenes").items()) {
        SCOPED_TRACE(name);
        const auto reference = load_png(dir / ("jade_" + name + ".png"));
        const double jade_flip = jade::flip::ldr_flip(reference, load_png(dir / ("web_" + name + "_jade.png")));
        const double physical_flip = jade::flip::ldr_flip(reference, load_png(dir / ("web_" + name + "_physical.png")));
        std::printf("%s, %s: LDR FLIP against jade render: JadeTranslucentMaterial %.4f, MeshPhysicalMaterial %.4f\n",
                    glb.filename().string().c_str(), name.c_str(), jade_flip, physical_flip);
        EXPECT_LE(jade_flip, bound.at(name));
        EXPECT_GT(physical_flip, 2.0 * jade_flip);  // the comparison can tell a different material apart
        if (shadows) {
            // The shadows' share: Jade's material without them is further from jade render.
            const double unshadowed_flip =
                jade::flip::ldr_flip(reference, load_png(dir / ("web_" + name + "_unshadowed.png")));
            std::printf("%s, %s: LDR FLIP against jade render: JadeTranslucentMaterial without shadows %.4f\n",
                        glb.filename().string().c_str(), name.c_str(), unshadowed_flip);
            // Asserted where the shadows' share is clear (the point scene's is 0.0002: printed).
            if (name != "point") EXPECT_GT(unshadowed_flip, jade_flip);
        }
    }
    if (frames > 0) {
        const nlohmann::json timing = read_json(dir / "web_timing.json");
        for (const auto& [name, t] : timing.at("scenes").items()) {
            const double ratio = t.at("ratio").get<double>();
            EXPECT_TRUE(ratio > 0.0 && std::isfinite(ratio)) << name;
        }
    }
}

void require_browser_side()
{
    if (const std::string why = missing_browser_side(); !why.empty()) {
        if (in_ci()) FAIL() << "CI=true and the browser side cannot run: " << why;
        GTEST_SKIP() << why;
    }
}

}  // namespace

// The committed demo file is what `jade bake` writes, and valid glTF.
TEST(Web, DemoFileIsValidGltf)
{
    const auto file = web("assets/bunny_blue_jewel.glb");
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    EXPECT_LT(std::filesystem::file_size(file), 1u << 20) << "the demo file is to stay under 1 MiB";
    std::string why;
    const auto reports = jade::test::run_gltf_validator({file}, &why);
    if (!reports) GTEST_SKIP() << why;
    ASSERT_EQ(reports->size(), 1u) << why;
    std::string issues;
    for (const auto& i : reports->front().issues) issues += "\n  " + i;
    EXPECT_EQ(reports->front().errors, 0) << issues;
    EXPECT_EQ(reports->front().warnings, 0) << issues;
    // The file carries every input of the default shading and the material (docs/gltf.md).
    const auto gltf = jade::test::read_gltf_file(file);
    const auto& primitive = gltf.doc.at("meshes").at(0).at("primitives").at(0);
    for (const char* attribute : {"_TM", "_THICKNESS", "_SCATTERING_NORMAL", "_NORMAL_SPREAD"})
        EXPECT_TRUE(primitive.at("attributes").contains(attribute)) << attribute;
    const auto& material = gltf.doc.at("materials").at(primitive.at("material").get<size_t>());
    EXPECT_EQ(material.at("extensions").at("JADE_materials_translucency").at("name"), "blue-jewel");
}

// The Figure 1 bunny (blue-jewel), front- and back-lit and under a point light from behind, and
// the frame times, with both sides' defaults: shadows on, the path per vertex on this mesh.
// Measured (512x512, 4x MSAA both sides): front 0.0017, back 0.0031, point 0.0022; the bounds are
// about twice that. What is left is where the two rasterisers, MSAA resolves (three.js resolves
// the sRGB-encoded canvas, Jade the linear image) and exp/pow differ, mostly on silhouettes. A
// wrong formula or input costs more: the web material without shadows measured 0.0038 and 0.0040
// (asserted: further than with them), with the baked thickness alone for the path (no depth
// tiles) the back scene 0.027, and three.js's MeshPhysicalMaterial with the same colour,
// roughness and ior 0.072, 0.108 and 0.075.
TEST(Web, JadeMaterialMatchesJadeRender)
{
    require_browser_side();
    if (testing::Test::HasFatalFailure() || testing::Test::IsSkipped()) return;
    compare_with_jade_render(web("assets/bunny_blue_jewel.glb"), jade::test::test_folder("web"),
                             {{"front", 0.004}, {"back", 0.006}, {"point", 0.005}}, 12, "auto", true);
}

// Another material through the same path: the demo file re-baked with marble (white, its own
// transmission constants) and strength 0.3, so that t > 0.3² everywhere and the web material, as
// Jade, drops the small-t closed form and sums 3 Fourier terms (choose_terms) instead of 6.
// The path per fragment and no shadows on both sides (jade render --no-shadows). Measured: front
// 0.0028, back 0.0035, point 0.0024 (MeshPhysicalMaterial 0.073, 0.040, 0.037); the bounds about
// 2.5 times that.
TEST(Web, AnotherMaterialMatchesJadeRender)
{
    require_browser_side();
    if (testing::Test::HasFatalFailure() || testing::Test::IsSkipped()) return;
    const auto dir = jade::test::test_folder("web");
    std::filesystem::create_directories(dir);
    const auto glb = dir / "bunny_marble.glb";
    const auto r = jade::test::run_cli({"bake", web("assets/bunny_blue_jewel.glb").string(), "--material", "marble",
                                        "--strength", "0.3", "--out", glb.string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    compare_with_jade_render(glb, dir, {{"front", 0.008}, {"back", 0.008}, {"point", 0.008}}, 0, "fragment", false);
}
