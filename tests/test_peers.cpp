// The peers' shading modes (docs/peers.md) against independent references. Filament's
// subsurface model: the rendered pixels against a float64 evaluation of the published formula
// (google/filament shading_model_subsurface.fs) on the same rasterised inputs, its thick limit
// against Lambert, and the inputs Jade derives from a medium against the rule written by hand.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/bake.hpp>
#include <jade/material.hpp>
#include <jade/render.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace jade;
using jade::test::GpuTest;

namespace {

class Peers : public GpuTest {};

constexpr double kPi = std::numbers::pi;

const PreparedMesh& unit_sphere()
{
    static PreparedMesh m = prepare_mesh(procedural::sphere(1.0f, 48, 96));
    return m;
}

// A matte material of albedo (0.8, 0.6, 0.5) whose medium has σ_tr = (1, 2, 4) per mesh unit: by
// the rule of docs/peers.md subsurfaceColor = (1 − k_d) σ_min/σ_tr = (0.2 · 1, 0.4 / 2, 0.5 / 4)
// and thickness = min(t̄ · σ_min/2, 1) = min(t̄/2, 1).
Material filament_material()
{
    Material m = burley_material(glm::dvec3(0.1), glm::vec3(0.8f, 0.6f, 0.5f), "filament test");
    m.specular = 0.0f;  // the lobe is every mode's and tested in test_render; this checks the rest
    m.transmission.sigma_tr = glm::vec3(1.0f, 2.0f, 4.0f);
    return m;
}
constexpr double kSubsurfaceColor[3] = {0.2, 0.2, 0.125};
constexpr double kPower = 12.234;  // Filament's default subsurfacePower

// Filament's per-light sum in float64 (the formula as published, written here on its own):
// (k_d/π) NoL E + subsurfaceColor · mix(back, 1, forward) · (1 − thickness)/π · E.
glm::dvec3 filament_f64(glm::dvec3 n, glm::dvec3 p, glm::dvec3 eye, double thickness, const Material& m,
                        std::span<const Light> lights)
{
    n = glm::normalize(n);
    const glm::dvec3 v = glm::normalize(eye - p);
    glm::dvec3 out(0.0);
    for (const Light& light : lights) {
        glm::dvec3 l = glm::dvec3(light.vector), e = glm::dvec3(light.color);
        if (light.type == Light::Type::Point) {
            l -= p;
            e /= glm::dot(l, l);
        }
        l = glm::normalize(l);
        const double no_l = std::clamp(glm::dot(n, l), 0.0, 1.0);
        const double forward = std::exp2(kPower * (std::clamp(glm::dot(v, -l), 0.0, 1.0) - 1.0));
        const double back = 0.5 * std::clamp(no_l * thickness + 1.0 - thickness, 0.0, 1.0);
        const double subsurface = (back + (1.0 - back) * forward) * (1.0 - thickness);
        for (int c = 0; c < 3; ++c)
            out[c] += (double(m.albedo[c]) / kPi * no_l + kSubsurfaceColor[c] * subsurface / kPi) * e[c];
    }
    return out;
}

}  // namespace

TEST(FilamentInputs, DerivedFromTheMediumByTheDocumentedRule)
{
    const FilamentSubsurface f = filament_subsurface(filament_material());
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(f.color[c], float(kSubsurfaceColor[c]));
    EXPECT_FLOAT_EQ(f.thickness_per_unit, 0.5f);
    EXPECT_FLOAT_EQ(f.power, float(kPower));
    // The ramp 1 − t/L with L = 1/thickness_per_unit carries ∫ e^{−σ_min t} dt = 1/σ_min.
    EXPECT_NEAR(0.5 / f.thickness_per_unit, 1.0 / 1.0, 1e-12);
    // No medium: 1 − k_d, grey (the renderer then uses Filament's default thickness 0.5).
    const FilamentSubsurface none =
        filament_subsurface(burley_material(glm::dvec3(0.1), glm::vec3(0.75f, 0.5f, 0.25f), "plain"));
    EXPECT_EQ(none.color, glm::vec3(0.25f, 0.5f, 0.75f));
    EXPECT_EQ(none.thickness_per_unit, 0.0f);
}

// Every covered pixel of a sphere with a thickness that varies over it (linear in y, so exact
// under interpolation; 0.2 to 1.8 mesh units, Filament's thickness 0.1 to 0.9, below the clamp
// that the mode applies per vertex: FilamentExtremeThicknessAndMediaRenderFinite has it), lit by a light behind it (forward scattering towards the eye) and a
// point light in front, against filament_f64 on the rasterised position, normal and thickness.
// Also the constant thickness of RenderSettings::filament_thickness. float32 against float64:
// within 1e-5 of the brightest pixel (measured 2.3e-7 and 2.1e-7: a few float32 roundings).
TEST_F(Peers, FilamentMatchesFloat64FormulaOnEveryPixel)
{
    const PreparedMesh& mesh = unit_sphere();
    std::vector<float> thickness(mesh.vertex_count());
    for (size_t i = 0; i < thickness.size(); ++i) thickness[i] = 0.2f + 0.8f * (mesh.positions[i].y + 1.0f);
    Renderer r(context());
    r.set_mesh(mesh, {}, thickness);
    const Material m = filament_material();
    r.set_material(m);
    const Camera camera{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f};
    const std::vector<Light> lights = {Light::directional({0.3f, 0.4f, -1.0f}, glm::vec3(3.0f)),
                                       Light::point({2.0f, 1.0f, 3.0f}, glm::vec3(20.0f, 15.0f, 10.0f))};
    RenderSettings s;
    s.width = s.height = 96, s.samples = 1, s.float32 = true, s.transparent_background = true;
    s.mode = ShadingMode::Filament, s.shadows = false;
    const ShadingInputs in = dev::shading_inputs(r, camera, lights, s);
    for (const float constant : {-1.0f, 0.5f}) {
        s.filament_thickness = constant;
        const RenderedImage img = r.render(camera, lights, s);
        double worst = 0.0, peak = 0.0, sum_subsurface = 0.0;
        size_t covered = 0;
        for (uint32_t y = 0; y < img.height; ++y)
            for (uint32_t x = 0; x < img.width; ++x) {
                const size_t p = size_t(y) * img.width + x;
                if (in.position[p].w < 1.0f) continue;  // background
                const double baked = in.normal[p].w;
                const double th = constant >= 0.0f ? constant : std::min(baked * 0.5, 1.0);
                const glm::dvec3 ref = filament_f64(glm::dvec3(in.normal[p]), glm::dvec3(in.position[p]),
                                                    glm::dvec3(camera.eye), th, m, lights);
                for (int c = 0; c < 3; ++c) {
                    worst = std::max(worst, std::abs(double(img.pixel(x, y)[c]) - ref[c]));
                    peak = std::max(peak, ref[c]);
                }
                sum_subsurface += 1.0 - th;
                ++covered;
            }
        std::printf("thickness %s: %zu pixels, max |GPU - float64| %.3g of peak %.3g\n",
                    constant < 0.0f ? "baked" : "0.5", covered, worst, peak);
        ASSERT_GT(covered, 4000u);
        EXPECT_GT(sum_subsurface, 0.1 * double(covered));  // the subsurface term is really there
        EXPECT_LT(worst, 1e-5 * peak);
    }
}

// Thickness 1 leaves Filament's BRDF alone: the image is Lambert's (with shadows on, the same
// shadows), up to float rounding.
TEST_F(Peers, FilamentThickLimitIsLambert)
{
    Renderer r(context());
    r.set_mesh(unit_sphere());
    r.set_material(filament_material());
    const Camera camera{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f};
    const std::vector<Light> lights = {Light::directional({0.3f, 0.4f, -1.0f}, glm::vec3(3.0f)),
                                       Light::directional({-0.5f, 0.2f, 1.0f}, glm::vec3(2.0f))};
    RenderSettings s;
    s.width = s.height = 64, s.float32 = true;
    s.mode = ShadingMode::Lambert;
    const RenderedImage lambert = r.render(camera, lights, s);
    s.mode = ShadingMode::Filament, s.filament_thickness = 1.0f;
    const RenderedImage thick = r.render(camera, lights, s);
    s.filament_thickness = 0.0f;
    const RenderedImage thin = r.render(camera, lights, s);
    double worst = 0.0, gained = 0.0;
    for (size_t i = 0; i < lambert.rgba.size(); ++i) {
        worst = std::max(worst, double(std::abs(thick.rgba[i] - lambert.rgba[i])));
        gained += double(thin.rgba[i] - lambert.rgba[i]);
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(gained, 1.0);  // thickness 0: the subsurface light is added
}

// Extreme inputs stay finite: thicknesses of 0, 1e-30 and 3e38 mesh units side by side, and
// media whose σ_tr spans 1e-30 to 3e38 per mesh unit; a thickness far past the medium's reach is
// Lambert's image.
TEST_F(Peers, FilamentExtremeThicknessAndMediaRenderFinite)
{
    const PreparedMesh& mesh = unit_sphere();
    std::vector<float> mixed(mesh.vertex_count()), huge(mesh.vertex_count(), 3e38f);
    const float values[] = {0.0f, 1e-30f, 3e38f};
    for (size_t i = 0; i < mixed.size(); ++i) mixed[i] = values[i % 3];
    const Camera camera{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f};
    const std::vector<Light> lights = {Light::directional({0.3f, 0.4f, -1.0f}, glm::vec3(3.0f)),
                                       Light::directional({-0.5f, 0.2f, 1.0f}, glm::vec3(2.0f))};
    RenderSettings s;
    s.width = s.height = 48, s.float32 = true, s.mode = ShadingMode::Filament;
    Renderer r(context());
    for (const glm::vec3 sigma : {glm::vec3(1e-30f, 1.0f, 1e30f), glm::vec3(3e38f), glm::vec3(1e-30f)}) {
        Material m = filament_material();
        m.transmission.sigma_tr = sigma;
        r.set_material(m);
        r.set_mesh(mesh, {}, mixed);
        const RenderedImage img = r.render(camera, lights, s);
        for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v)) << "sigma_tr " << sigma.x << " " << sigma.z;
    }
    Material m = filament_material();
    r.set_material(m);
    r.set_mesh(mesh, {}, huge);
    const RenderedImage thick = r.render(camera, lights, s);
    s.mode = ShadingMode::Lambert;
    const RenderedImage lambert = r.render(camera, lights, s);
    double worst = 0.0;
    for (size_t i = 0; i < thick.rgba.size(); ++i)
        worst = std::max(worst, double(std::abs(thick.rgba[i] - lambert.rgba[i])));
    EXPECT_LT(worst, 1e-6);
}

TEST_F(Peers, FilamentThicknessOutsideItsRangeIsRefused)
{
    Renderer r(context());
    r.set_mesh(unit_sphere());
    r.set_material(filament_material());
    const Light light = Light::directional({0, 0, 1}, glm::vec3(1.0f));
    RenderSettings s;
    s.width = s.height = 16, s.mode = ShadingMode::Filament, s.filament_thickness = 1.5f;
    const std::string what = test::error_of([&] { r.render(Camera{}, {&light, 1}, s); });
    EXPECT_NE(what.find("filament_thickness"), std::string::npos) << what;
    EXPECT_EQ(dev::parse_shading_mode("filament"), ShadingMode::Filament);
    EXPECT_EQ(dev::shading_mode_name(ShadingMode::Filament), "filament");
}

// `jade bench render` times every mode in one run, each with its ratio to Lambert and its
// fetches per shaded pixel; a mode it does not know is named.
TEST(PeersCli, BenchRenderTimesEveryModeAgainstLambert)
{
    const auto r = test::run_cli({"bench", "render", "--validation", "--quality", "draft", "--repeat", "1", "--sizes",
                                  "32,48x24", "--ao-rays", "8"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* row : {"32x32      lambert", "32x32      curvature", "32x32      tm", "32x32      filament",
                            "48x24      lambert", "48x24      filament"})
        EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;
    EXPECT_NE(r.output.find("1.000x"), std::string::npos) << r.output;  // Lambert against itself
    const auto bad = test::run_cli({"bench", "render", "--modes", "lambert,phong"});
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("phong"), std::string::npos) << bad.output;
    const auto fidelity = test::run_cli({"fidelity", "--modes", "default,separabl"});
    EXPECT_NE(fidelity.exit_code, 0);
    EXPECT_NE(fidelity.output.find("'separabl' is not one of lambert, curvature, tm, default, filament"),
              std::string::npos)
        << fidelity.output;
}
