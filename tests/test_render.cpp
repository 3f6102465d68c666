// The renderer: analytic values on a sphere, the
// t_m path against Lambert, the strength's effect past the terminator, golden images of the
// bunny in the four modes, errors, and the CLI.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/dev/material.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/bake.hpp>
#include <jade/io.hpp>
#include <jade/dev/lut.hpp>
#include <jade/render.hpp>

// Golden PNGs are read with OpenImageIO, which jade::io links already (jade/io.hpp has no reader).
#include <OpenImageIO/imageio.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

using namespace jade;
using jade::test::GpuTest;

namespace {

class Render : public GpuTest {};

const PreparedMesh& unit_sphere()
{
    static PreparedMesh m = prepare_mesh(procedural::sphere(1.0f, 48, 96));
    return m;
}

Material matte(float strength = 1.0f)
{
    Material m = burley_material(glm::dvec3(0.1), glm::vec3(1.0f), "matte");
    m.specular = 0.0f;
    m.strength = strength;
    return m;
}

RenderSettings settings(uint32_t size, ShadingMode mode)
{
    RenderSettings s;
    s.width = s.height = size;
    s.mode = mode;
    s.float32 = true;
    s.transparent_background = true;  // alpha = coverage: tells the surface from the background
    return s;
}

const Camera kFront{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f};

double centre_red(const RenderedImage& img) { return img.pixel(img.width / 2, img.height / 2)[0]; }

// The bunny of the golden images: prepared once, t_m baked once at draft quality.
struct Bunny {
    PreparedMesh mesh;
    Material material;
    std::vector<glm::vec3> tm;
};
const Bunny& bunny(Context& ctx)
{
    static Bunny b = [&] {
        Bunny out;
        out.mesh = prepare_mesh(load_mesh(test::asset("bunny00.off")));
        out.material = material_preset("blue-jewel", 100.0 / out.mesh.diagonal);
        Baker baker(ctx);
        out.tm = baker.bake(out.mesh, out.material, BakeSettings::preset(Quality::Draft)).tm;
        return out;
    }();
    return b;
}

std::vector<uint8_t> to_srgb8(const RenderedImage& img)  // as jade::save_image writes PNGs
{
    std::vector<uint8_t> out(img.rgba.size());
    for (size_t i = 0; i < out.size(); ++i) {
        float v = std::clamp(img.rgba[i], 0.0f, 1.0f);
        if (i % 4 != 3) v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
        out[i] = uint8_t(std::lround(v * 255.0f));
    }
    return out;
}

std::vector<uint8_t> read_png(const std::filesystem::path& path, uint32_t width, uint32_t height)
{
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    if (uint32_t(spec.width) != width || uint32_t(spec.height) != height || spec.nchannels != 4) return {};
    std::vector<uint8_t> pixels(size_t(width) * height * 4);
    if (!in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, pixels.data())) return {};
    return pixels;
}

// Compares with tests/data/golden/NAME.png: mean absolute error and 99th percentile of the
// per-pixel maximum channel error, in 8-bit sRGB steps. JADE_UPDATE_GOLDEN=1 rewrites it.
void expect_matches_golden(const RenderedImage& img, const std::string& name)
{
    const auto golden_path = test::data("golden/" + name + ".png");
    if (const char* update = std::getenv("JADE_UPDATE_GOLDEN"); update && std::string(update) == "1") {
        save_image(golden_path, int(img.width), int(img.height), img.rgba);
        // Writing is not checking: the run fails, so the mode can never pass CI by itself.
        ADD_FAILURE() << "JADE_UPDATE_GOLDEN=1: wrote " << golden_path << " instead of comparing; look at it before "
                      << "committing, then run the test again without the variable";
        return;
    }
    const std::vector<uint8_t> actual = to_srgb8(img), golden = read_png(golden_path, img.width, img.height);
    ASSERT_FALSE(golden.empty()) << golden_path << " is missing or not " << img.width << "x" << img.height
                                 << " RGBA (JADE_UPDATE_GOLDEN=1 writes it)";
    std::vector<int> pixel_error(size_t(img.width) * img.height);
    double sum = 0;
    RenderedImage diff = img;
    for (size_t p = 0; p < pixel_error.size(); ++p) {
        int e = 0;
        for (int c = 0; c < 4; ++c) e = std::max(e, std::abs(int(actual[4 * p + c]) - int(golden[4 * p + c])));
        pixel_error[p] = e;
        sum += e;
        for (int c = 0; c < 3; ++c) diff.rgba[4 * p + c] = std::min(1.0f, float(e) * 4.0f / 255.0f);
        diff.rgba[4 * p + 3] = 1.0f;
    }
    const double mean = sum / double(pixel_error.size());
    std::nth_element(pixel_error.begin(), pixel_error.begin() + pixel_error.size() * 99 / 100, pixel_error.end());
    const int p99 = pixel_error[pixel_error.size() * 99 / 100];
    std::printf("%s: mean abs error %.3f, 99th percentile %d (8-bit sRGB steps)\n", name.c_str(), mean, p99);
    if (mean > 1.0 || p99 > 12) {
        const auto actual_path = test::out("render/" + name + "_actual.png"),
                   diff_path = test::out("render/" + name + "_diff.png");
        save_image(actual_path, int(img.width), int(img.height), img.rgba);
        save_image(diff_path, int(img.width), int(img.height), diff.rgba);
        ADD_FAILURE() << name << ": differs from " << golden_path << " (mean " << mean << ", p99 " << p99 << "); wrote "
                      << actual_path << " and " << diff_path;
    }
}

}  // namespace

// A sphere lit from the camera with E = π and albedo 1 has radiance cos θ: 1 at the centre.
TEST_F(Render, LambertSphereCentreHasAnalyticRadiance)
{
    Renderer r(context());
    r.set_mesh(unit_sphere());
    r.set_material(matte());
    const Light light = Light::directional({0, 0, 1}, glm::vec3(std::numbers::pi_v<float>));
    RenderedImage img = r.render(kFront, {&light, 1}, settings(65, ShadingMode::Lambert));
    EXPECT_NEAR(centre_red(img), 1.0, 5e-3);
    EXPECT_EQ(img.pixel(0, 0)[3], 0.0f);  // background: transparent
    EXPECT_GT(img.gpu_ms, 0.0);
}

// A point light at distance d: E = I/d² (inverse square).
TEST_F(Render, PointLightFallsOffWithInverseSquare)
{
    Renderer r(context());
    r.set_mesh(unit_sphere());
    r.set_material(matte());
    const Light light =
        Light::point({0, 0, 3}, glm::vec3(4.0f * std::numbers::pi_v<float>));  // 2 units from the surface
    RenderedImage img = r.render(kFront, {&light, 1}, settings(65, ShadingMode::Lambert));
    EXPECT_NEAR(centre_red(img), 1.0, 5e-3);
}

TEST_F(Render, TmWithZeroStrengthIsLambert)
{
    Renderer r(context());
    std::vector<glm::vec3> tm(unit_sphere().vertex_count());
    for (size_t i = 0; i < tm.size(); ++i)
        tm[i] = glm::vec3(0.3f, 1.0f, 2.5f) * (0.5f + 0.5f * unit_sphere().positions[i].y);
    r.set_mesh(unit_sphere(), tm);
    Material m = material_preset("blue-jewel", 100.0 / 3.46);  // coloured profiles: the 3-fetch path
    m.strength = 0.0f;
    // The poster's limit: no boundary transmittance (a medium's material multiplies the diffuse
    // term by it, so t_m = 0 is Lambert × T(N·L)·T(N·V) there, tests/test_thickness.cpp).
    m.boundary_transmittance = false;
    r.set_material(m);
    const auto lights = default_lights(kFront);
    RenderedImage lambert = r.render(kFront, lights, settings(128, ShadingMode::Lambert));
    RenderedImage tm_zero = r.render(kFront, lights, settings(128, ShadingMode::Tm));
    double worst = 0;
    for (size_t i = 0; i < lambert.rgba.size(); ++i) {
        const double a = lambert.rgba[i], b = tm_zero.rgba[i];
        worst = std::max(worst, std::abs(a - b) / (1e-3 * std::max(std::abs(a), std::abs(b)) + 1e-5));
    }
    EXPECT_LE(worst, 1.0) << "per-pixel difference beyond 1e-3 relative + 1e-5 absolute";
}

// Back of the terminator: with the light from +x, the left half of the sphere receives light
// only through the LUT's Gaussian, more the larger strength · t_m.
TEST_F(Render, StrengthBrightensShadowSideMonotonically)
{
    Renderer r(context());
    r.set_mesh(unit_sphere(), std::vector<glm::vec3>(unit_sphere().vertex_count(), glm::vec3(0.2f, 0.5f, 1.0f)));
    const Light light = Light::directional({1, 0, 0}, glm::vec3(3.0f));
    double previous = -1;
    for (float strength : {0.0f, 0.5f, 1.0f, 2.0f}) {
        Material m = matte(strength);
        m.profile[0] = ChannelProfile::burley(0.05);  // RGB material: three channels, three fetches
        r.set_material(m);
        RenderedImage img = r.render(kFront, {&light, 1}, settings(96, ShadingMode::Tm));
        double shadow = 0;
        for (uint32_t y = 0; y < img.height; ++y)
            for (uint32_t x = 0; x < img.width / 2 - 2; ++x)
                if (img.pixel(x, y)[3] > 0.0f) shadow += img.pixel(x, y)[0] + img.pixel(x, y)[1] + img.pixel(x, y)[2];
        std::printf("strength %.1f: shadow-side sum %.4f\n", strength, shadow);
        if (strength == 0.0f) EXPECT_LT(shadow, 1e-3);  // Lambert: black past the terminator
        EXPECT_GT(shadow, previous);
        previous = shadow;
    }
}

// Every lit pixel of the t_m path against the float64 f(cos θ, t): the shader's LUT read
// (quads, indices, bilinear weights) as accurate as the LUT itself (≤ 1e-4). cos θ per pixel
// comes from two Lambert renders of the same sphere (light l and −l: max(±cos θ, 0)), one
// sample per pixel, so both modes see the same fragments; t_m is constant, so t is exact.
TEST_F(Render, TmMatchesFloat64LutReferenceOnEveryPixel)
{
    Renderer r(context());
    const glm::vec3 t(2e-4f, 0.05f, 1.5f);  // small t (kink), mid, large: three LUT rows
    r.set_mesh(unit_sphere(), std::vector<glm::vec3>(unit_sphere().vertex_count(), t));
    const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 0.3f, 0.6f));
    const Light front = Light::directional(dir, glm::vec3(std::numbers::pi_v<float>));  // albedo 1: L = F
    const Light back = Light::directional(-dir, glm::vec3(std::numbers::pi_v<float>));
    for (bool grey : {true, false}) {
        Material m = matte();
        if (!grey) m.profile[2] = ChannelProfile::burley(0.1 * (1 + 1e-12));  // the three-fetch pipeline
        r.set_material(m);
        RenderSettings s = settings(96, ShadingMode::Lambert);
        s.samples = 1;
        // F alone: this 48 × 96 sphere's facets shadow its smooth terminator by up to 7e-4 of F.
        s.shadows = false;
        RenderedImage lit = r.render(kFront, {&front, 1}, s), unlit = r.render(kFront, {&back, 1}, s);
        s.mode = ShadingMode::Tm;
        RenderedImage tm = r.render(kFront, {&front, 1}, s);
        double worst = 0;
        size_t pixels = 0;
        for (uint32_t y = 0; y < s.height; ++y)
            for (uint32_t x = 0; x < s.width; ++x) {
                if (tm.pixel(x, y)[3] == 0.0f) continue;
                const double c = double(lit.pixel(x, y)[0]) - double(unlit.pixel(x, y)[0]);
                for (int ch = 0; ch < 3; ++ch) {
                    const double tc = grey ? double(t[0]) : double(t[ch]);
                    worst = std::max(worst, std::abs(double(tm.pixel(x, y)[ch]) - lut_reference(c, tc)));
                }
                ++pixels;
            }
        std::printf("%s: %zu pixels, max |F - f_ref| = %.3g\n", grey ? "grey" : "rgb", pixels, worst);
        EXPECT_GT(pixels, 3000u);
        EXPECT_LE(worst, 1e-4);
    }
}

// A grey material takes the one-fetch pipeline; the result equals the three-fetch one.
TEST_F(Render, GreyMaterialMatchesThreeChannelPath)
{
    Renderer r(context());
    r.set_mesh(unit_sphere(), std::vector<glm::vec3>(unit_sphere().vertex_count(), glm::vec3(0.7f)));
    const auto lights = figure1_lights(kFront);
    Material grey = matte();
    ASSERT_TRUE(dev::is_grey(grey));
    r.set_material(grey);
    RenderedImage one = r.render(kFront, lights, settings(64, ShadingMode::Tm));
    Material rgb = grey;
    rgb.profile[2] = ChannelProfile::burley(0.1 * (1 + 1e-12));  // not grey, same t_m and LUT
    ASSERT_FALSE(dev::is_grey(rgb));
    r.set_material(rgb);
    RenderedImage three = r.render(kFront, lights, settings(64, ShadingMode::Tm));
    for (size_t i = 0; i < one.rgba.size(); ++i) ASSERT_NEAR(one.rgba[i], three.rgba[i], 1e-6) << "float " << i;
}

// t_m given per render vertex (as read from a baked file) is carried to the welded vertices.
TEST_F(Render, TriangleMeshWithPerRenderVertexTmMatchesPrepared)
{
    const TriangleMesh mesh = procedural::sphere(1.0f, 24, 48);
    std::vector<glm::vec3> per_render(mesh.positions.size());
    for (size_t i = 0; i < per_render.size(); ++i) per_render[i] = glm::vec3(0.5f + 0.5f * mesh.positions[i].y);
    const PreparedMesh prepared = prepare_mesh(mesh);
    std::vector<glm::vec3> per_bake(prepared.vertex_count());
    for (size_t i = 0; i < per_bake.size(); ++i) per_bake[i] = glm::vec3(0.5f + 0.5f * prepared.positions[i].y);
    Renderer r(context());
    r.set_material(matte());
    const auto lights = figure1_lights(kFront);
    r.set_mesh(mesh, per_render);
    RenderedImage a = r.render(kFront, lights, settings(48, ShadingMode::Tm));
    r.set_mesh(prepared, per_bake);
    RenderedImage b = r.render(kFront, lights, settings(48, ShadingMode::Tm));
    for (size_t i = 0; i < a.rgba.size(); ++i) ASSERT_NEAR(a.rgba[i], b.rgba[i], 1e-5) << "float " << i;
}

TEST_F(Render, MeanCurvatureOfSphereIsInverseRadius)
{
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(2.0f, 64, 128));
    std::vector<float> h = mean_curvature(sphere, 0);
    std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
    EXPECT_NEAR(h[h.size() / 2], 0.5, 0.01);
}

TEST_F(Render, BadInputIsAnErrorNamingIt)
{
    Renderer r(context());
    const auto lights = default_lights(kFront);
    auto message = [&](auto&& f) {
        try {
            f();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(message([&] { r.render(kFront, lights, {}); }).find("set_mesh"), std::string::npos);
    EXPECT_NE(message([&] { r.set_mesh(unit_sphere(), std::vector<glm::vec3>(3)); }).find("t_m"), std::string::npos);
    r.set_mesh(unit_sphere());
    r.set_material(matte());
    RenderSettings s = settings(32, ShadingMode::Tm);
    s.samples = 3;
    EXPECT_NE(message([&] { r.render(kFront, lights, s); }).find("samples"), std::string::npos);
    Camera bad = kFront;
    bad.target = bad.eye;
    EXPECT_NE(message([&] { r.render(bad, lights, settings(32, ShadingMode::Tm)); }).find("camera"), std::string::npos);
    EXPECT_THROW(dev::parse_shading_mode("phong"), Error);
}

// The four modes in one test: the bunny is baked once (ctest runs each test in its own process).
TEST_F(Render, GoldenBunnyInFourModesUnderFigure1Lights)
{
    const Bunny& b = bunny(context());
    Renderer r(context());
    r.set_mesh(b.mesh, b.tm);
    r.set_material(b.material);
    const Camera camera = Camera::framing(b.mesh.bbox_min, b.mesh.bbox_max);
    for (ShadingMode mode :
         {ShadingMode::Lambert, ShadingMode::Curvature, ShadingMode::Tm, ShadingMode::TmFalseColor}) {
        RenderSettings s;
        s.width = s.height = 192;
        s.mode = mode;
        // A fixed colour-map range: the mesh's extreme values move with every bake change.
        s.false_color_min = 0.6f, s.false_color_max = 1.2f;
        std::string name = "bunny_" + std::string(dev::shading_mode_name(mode));
        std::replace(name.begin(), name.end(), '-', '_');
        SCOPED_TRACE(name);
        expect_matches_golden(r.render(camera, figure1_lights(camera), s), name);
    }
}

TEST(RenderCli, LambertPngAndFlagErrors)
{
    const auto out = test::out("render/cli_lambert.png");
    auto ok = test::run_cli({"render", test::asset("bunny00.off").string(), "--mode", "lambert", "--size", "64x48",
                             "--light", "dir:0,1,1:2,2,2", "--light", "point:0,1,2:5,5,5", "--out", out.string()});
    EXPECT_EQ(ok.exit_code, 0) << ok.output;
    EXPECT_TRUE(std::filesystem::exists(out)) << ok.output;
    auto bad = test::run_cli({"render", "--mode", "lambert", "--light", "spot:0,0,1:1,1,1"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.output.find("--light"), std::string::npos) << bad.output;
    auto bad_size = test::run_cli({"render", "--size", "64by64"});
    EXPECT_EQ(bad_size.exit_code, 2);
    EXPECT_NE(bad_size.output.find("--size"), std::string::npos) << bad_size.output;
}
