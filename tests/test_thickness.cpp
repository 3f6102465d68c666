// The thickness pass (inward cone rays, jade/bake.hpp ThicknessSettings) against its float64
// reference on the same rays and against analytic cases, in the static bake and DynamicBake;
// and the transmission term it feeds, against its formula on a back-lit slab.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/dev/material.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/bake.hpp>
#include <jade/io.hpp>
#include <jade/dev/reference.hpp>
#include <jade/render.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace jade;
using jade::test::GpuTest;

namespace {

Material translucent()
{
    Medium m;
    m.sigma_s = glm::dvec3(10.0), m.sigma_a = glm::dvec3(1.0);
    return Material::from_medium(m);
}

BakeSettings settings(uint32_t rays = 32)
{
    BakeSettings s = BakeSettings::preset(Quality::Draft);
    s.thickness.rays = rays;
    return s;
}

// E[h / cos θ] over the cone of half-angle θ_c, uniform in solid angle: h ln(1/cos θ_c)/(1 − cos θ_c).
double slab_mean(double h, double cone_degrees)
{
    const double c = std::cos(cone_degrees * std::numbers::pi / 180.0);
    return h * std::log(1.0 / c) / (1.0 - c);
}

}  // namespace

class Thickness : public GpuTest {};

TEST_F(Thickness, MatchesTheFloat64ReferenceOnTheSameRays)
{
    const PreparedMesh mesh = prepare_mesh(load_mesh(test::asset("bunny00.off")));
    Baker baker(context());
    const BakeResult r = baker.bake(mesh, translucent(), settings(32));
    ASSERT_EQ(r.thickness.size(), mesh.vertex_count());
    std::vector<uint32_t> at;
    for (uint32_t v = 0; v < mesh.vertex_count(); v += 37) at.push_back(v);
    const std::vector<double> ref = reference_thickness(mesh, settings(32).thickness, at);
    size_t close = 0;
    double worst = 0.0;
    for (size_t k = 0; k < at.size(); ++k) {
        const double g = r.thickness[at[k]], e = std::abs(g - ref[k]) / ref[k];
        ASSERT_TRUE(std::isfinite(g) && g > 0.0) << "vertex " << at[k];
        close += e <= 1e-4 ? 1 : 0;
        worst = std::max(worst, e);
    }
    // A ray that grazes an edge can hit the neighbouring triangle in float32 and not in float64.
    EXPECT_GE(double(close) / double(at.size()), 0.995) << "worst relative difference " << worst;
    EXPECT_LT(worst, 0.1);
}

TEST_F(Thickness, ASlabGivesItsThickness)
{
    const float h = 0.1f;
    const PreparedMesh slab = prepare_mesh(dev::procedural::box({-5.0f, -5.0f, -0.5f * h}, {5.0f, 5.0f, 0.5f * h}, 64));
    Baker baker(context());
    const BakeResult r = baker.bake(slab, translucent(), settings(64));
    const double expected = slab_mean(h, 60.0);
    int checked = 0;
    for (size_t v = 0; v < slab.vertex_count(); ++v) {
        const glm::vec3 p = slab.positions[v];
        if (std::abs(p.x) > 3.0f || std::abs(p.y) > 3.0f || std::abs(slab.normals[v].z) < 0.99f) continue;
        EXPECT_NEAR(r.thickness[v], expected, 0.01 * expected) << "vertex " << v << " at " << p.x << ", " << p.y;
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

TEST_F(Thickness, ASphereGivesItsMeanChord)
{
    // The chord at angle θ to the inward normal of a sphere of radius R is 2R cos θ; its mean over
    // the cone is R(1 + cos θ_c).
    const float radius = 2.0f;
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(radius, 96, 192));
    Baker baker(context());
    const BakeResult r = baker.bake(sphere, translucent(), settings(64));
    const double expected = radius * (1.0 + std::cos(std::numbers::pi / 3.0));
    double sum = 0.0;
    for (float t : r.thickness) {
        EXPECT_NEAR(t, expected, 0.03 * expected);  // the poles of the UV sphere are the worst
        sum += t;
    }
    EXPECT_NEAR(sum / double(r.thickness.size()), expected, 0.005 * expected);
}

TEST_F(Thickness, OpenMeshesCountMissesAsTheMaximumAndNoMediumMeansNoPass)
{
    const PreparedMesh grid = prepare_mesh(dev::procedural::grid(16, 0.1f));
    Baker baker(context());
    BakeSettings s = settings(16);
    const BakeResult r = baker.bake(grid, translucent(), s);
    for (float t : r.thickness) EXPECT_NEAR(t, s.thickness.max_distance_rel * grid.diagonal, 1e-6 * grid.diagonal);
    Material no_transmission = translucent();
    no_transmission.transmission.weight = no_transmission.transmission.diffusion_weight = 0.0f;
    EXPECT_TRUE(baker.bake(grid, no_transmission, s).thickness.empty());
    s.thickness.rays = 2000;
    EXPECT_THROW(baker.bake(grid, translucent(), s), Error);
}

TEST_F(Thickness, DynamicBakeKeepsItAndStillMeshesRebakeBitForBit)
{
    const PreparedMesh mesh = prepare_mesh(load_mesh(test::asset("ChineseDragon-10kv.off")));
    Baker baker(context());
    const BakeSettings s = settings(16);
    const BakeResult still = baker.bake(mesh, translucent(), s);
    DynamicBake rebake(baker, mesh, translucent(), s);
    ASSERT_NE(rebake.buffers().thickness, VK_NULL_HANDLE);
    const BakeResult first = rebake.bake(mesh.positions, mesh.normals, mesh.areas);
    const BakeResult second = rebake.bake(mesh.positions, mesh.normals, mesh.areas);
    ASSERT_EQ(first.thickness.size(), mesh.vertex_count());
    EXPECT_EQ(first.thickness, second.thickness);
    size_t same = 0;
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
        same += std::abs(first.thickness[v] - still.thickness[v]) <= 1e-5f * still.thickness[v] ? 1 : 0;
    EXPECT_GE(double(same) / double(mesh.vertex_count()), 0.995);  // the refitted tree's boxes round differently
    // Amortised: the slices must divide the thickness rays too.
    EXPECT_THROW(rebake.set_amortisation({3, 1}), Error);
}

TEST_F(Thickness, BackLitSlabShowsTheBallisticTransmittance)
{
    // A slab seen from +z with a directional light straight behind it: V·(−L) = 1 and −N·L = 1 at
    // the centre, so the pixel is weight · (n + 1)/(2π) · e^{−σ_t t̄} · E · (1 − F0)² (both
    // crossings of the boundary at normal incidence) with the diffuse and specular terms off.
    const float h = 0.1f;
    const PreparedMesh slab = prepare_mesh(dev::procedural::box({-5.0f, -5.0f, -0.5f * h}, {5.0f, 5.0f, 0.5f * h}, 64));
    Baker baker(context());
    Material m = translucent();
    m.albedo = glm::vec3(0.0f), m.specular = 0.0f;
    m.transmission.sigma_t = {5.0f, 10.0f, 20.0f};
    m.transmission.weight = 0.7f, m.transmission.diffusion_weight = 0.0f, m.transmission.lobe = 3.0f;
    m.transmission.normal_mix = 0.4f;
    const BakeResult r = baker.bake(slab, m, settings(64));
    Renderer renderer(context());
    renderer.set_mesh(slab, r.tm, r.thickness);
    renderer.set_material(m);
    Camera cam;
    cam.eye = {0.0f, 0.0f, 3.0f}, cam.target = {0.0f, 0.0f, 0.0f}, cam.fov_y_degrees = 10.0f;
    const std::vector<Light> lights = {Light::directional({0.0f, 0.0f, -1.0f}, glm::vec3(2.0f))};
    RenderSettings rs;
    rs.width = rs.height = 33, rs.float32 = true;
    const RenderedImage img = renderer.render(cam, lights, rs);
    const float* centre = img.pixel(16, 16);
    const double t = slab_mean(h, 60.0), lobe = (3.0 + 1.0) / (2.0 * std::numbers::pi);
    const double f0 = std::pow((double(m.ior) - 1.0) / (double(m.ior) + 1.0), 2.0), crossings = (1.0 - f0) * (1.0 - f0);
    for (int c = 0; c < 3; ++c) {
        const double expected = 0.7 * lobe * std::exp(-double(m.transmission.sigma_t[c]) * t) * 2.0 * crossings;
        EXPECT_NEAR(centre[c], expected, 0.01 * expected) << "channel " << c;
    }
    // Without the boundary the crossings are not there.
    m.boundary_transmittance = false;
    renderer.set_material(m);
    const RenderedImage bare = renderer.render(cam, lights, rs);
    EXPECT_NEAR(bare.pixel(16, 16)[1] / centre[1], 1.0 / crossings, 0.002) << "without boundary_transmittance";
    m.boundary_transmittance = true;
    // The diffused part alone: the dipole gather over the light's entry layer (transmission.glsl,
    // diffused_light) against a float64 quadrature of the same integral over the slab's far side,
    // leaving as a Lambertian emitter (1/π) whatever the lobe. The slab is 10 units wide, the
    // gather's disk h + 3/min σ_tr = 3.1 in radius, all of it slab: W = 6.2 for the buckling.
    m.transmission.weight = 0.0f, m.transmission.diffusion_weight = 0.5f;
    m.transmission.sigma_s_reduced = {10.0f, 5.0f, 2.0f};
    m.transmission.sigma_tr = {1.0f, 3.0f, 9.0f};
    m.transmission.source_depth = {0.02f, 0.05f, 0.1f};
    m.transmission.extrapolation = {0.01f, 0.03f, 0.06f};
    renderer.set_material(m);
    const RenderedImage diffused = renderer.render(cam, lights, rs);
    const double alpha = std::max(double(m.roughness) * double(m.roughness), 1e-3);
    const double mean_entry = 1.0 - f0 - (std::max(1.0 - alpha, f0) - f0) / 21.0;
    for (int c = 0; c < 3; ++c) {
        const double zb = m.transmission.extrapolation[c], zr = m.transmission.source_depth[c] - zb;
        const double albedo = double(m.transmission.sigma_s_reduced[c]) * zr, reach = double(h) + 3.0;
        const double buckling = std::numbers::pi / (2.0 * reach + 2.0 * zb);
        const double sigma = std::sqrt(std::pow(double(m.transmission.sigma_tr[c]), 2) + 2.0 * buckling * buckling);
        // A source at depth a below the far side (its image a + 2z_b beyond), at ρ across.
        auto flux = [&](double a, double rho) {
            a = std::max(a, 0.0);
            double out = 0.0;
            for (double depth : {a, a + 2.0 * zb}) {
                const double r = std::sqrt(rho * rho + depth * depth);
                out += depth * (1.0 + sigma * r) * std::exp(-sigma * r) / (r * r * r);
            }
            return out;
        };
        double exitance = 0.0;
        const int steps = 200000;
        for (int i = 0; i < steps; ++i) {
            const double rho = (i + 0.5) * reach / steps;
            const double share = double(h) / std::sqrt(rho * rho + double(h) * double(h));
            const double profile =
                albedo / (4.0 * std::numbers::pi) * std::max(flux(h - zr, rho) - flux(h + zr + 2.0 * zb, rho), 0.0);
            exitance += 2.0 * std::numbers::pi * rho * (reach / steps) * share * profile;
        }
        const double expected = 0.5 * exitance * mean_entry * 2.0 * (1.0 - f0) / std::numbers::pi;
        EXPECT_NEAR(diffused.pixel(16, 16)[c], expected, 0.03 * expected) << "diffused, channel " << c;
    }
    // Off with RenderSettings::transmission = false; and a light in front gives no forward lobe
    // (the eye is inside the slab's bounding sphere, so the term is drawn: the diffused part,
    // a Lambertian emitter, would light the front face, so it is off here).
    rs.transmission = false;
    EXPECT_LT(renderer.render(cam, lights, rs).pixel(16, 16)[0], 1e-4f);
    rs.transmission = true;
    m.transmission.weight = 0.7f, m.transmission.diffusion_weight = 0.0f;
    renderer.set_material(m);
    const std::vector<Light> front = {Light::directional({0.0f, 0.0f, 1.0f}, glm::vec3(2.0f))};
    EXPECT_EQ(renderer.render(cam, front, rs).pixel(16, 16)[0], 0.0f);
}

TEST_F(Thickness, LightPathCountsTheMediumAndNotTheAirBetweenParts)
{
    // Slabs stacked along z with air between them, lit from straight behind (−z) and seen from
    // +z: the front slab's path (Renderer::shading_inputs) is the medium along the light's line, slab by slab, with the gaps
    // left out, for up to two parts (four surfaces); from a third part on, the rest of the line
    // counts as medium. The same for a point light on the axis behind the slabs (a perspective
    // tile: its layers hold distances from the light, and on the axis the ray is the line).
    auto stack = [](std::initializer_list<std::pair<float, float>> slabs) {
        TriangleMesh mesh;
        mesh.name = "slab stack";
        for (const auto& [lo, hi] : slabs) {
            const TriangleMesh box = dev::procedural::box({-5.0f, -5.0f, lo}, {5.0f, 5.0f, hi}, 16);
            const uint32_t base = uint32_t(mesh.positions.size());
            mesh.positions.insert(mesh.positions.end(), box.positions.begin(), box.positions.end());
            for (uint32_t i : box.indices) mesh.indices.push_back(base + i);
        }
        return prepare_mesh(mesh);
    };
    Baker baker(context());
    const Material m = translucent();
    // Both samplings of the path: the slabs are flat where the camera looks, so they agree.
    for (dev::LightPathSampling sampling : {dev::LightPathSampling::PerFragment, dev::LightPathSampling::PerVertex})
        for (const Light& light : {Light::directional({0.0f, 0.0f, -1.0f}, glm::vec3(1.0f)),
                                   Light::point({0.0f, 0.0f, -12.0f}, glm::vec3(150.0f))}) {
            SCOPED_TRACE(std::string(dev::light_path_sampling_name(sampling)) +
                         (light.type == Light::Type::Point ? ", point light" : ", directional light"));
            RendererOptions options;
            dev::set_study(options, {.light_path = sampling});
            Renderer renderer(context(), options);
            renderer.set_material(m);
            Camera cam;
            cam.eye = {0.0f, 0.0f, 3.0f}, cam.target = {0.0f, 0.0f, 0.0f}, cam.fov_y_degrees = 10.0f;
            const std::vector<Light> lights = {light};
            RenderSettings rs;
            rs.width = rs.height = 33;
            auto centre_path = [&](const PreparedMesh& mesh) {
                const BakeResult r = baker.bake(mesh, m, settings(16));
                renderer.set_mesh(mesh, r.tm, r.thickness);
                const ShadingInputs in = dev::shading_inputs(renderer, cam, lights, rs);
                EXPECT_EQ(in.transmits.at(0), 1);
                return double(in.path.at(16 * in.width + 16));
            };
            // Depth is stored as float32 over the light's box (twice the bounding sphere's radius).
            // One part: the light's 0.1 is below the local thickness t̄, which the path never goes under.
            const double one_part = centre_path(stack({{0.0f, 0.1f}}));
            EXPECT_NEAR(one_part, slab_mean(0.1, 60.0), 3e-3);
            // 0.1 in front, 0.3 of air, 0.2 behind: 0.3 of medium (the depth from the entry is 0.6).
            const double two_parts = centre_path(stack({{0.0f, 0.1f}, {-0.5f, -0.3f}}));
            EXPECT_NEAR(two_parts, 0.3, 1e-3);
            // A third part, nearest to the light: 0.05 and 0.2 of medium in the first two parts the light
            // meets; after them, the 0.3 of air and the 0.1 of the front slab count.
            const double three_parts = centre_path(stack({{0.0f, 0.1f}, {-0.5f, -0.3f}, {-0.75f, -0.7f}}));
            EXPECT_NEAR(three_parts, 0.05 + 0.2 + 0.3 + 0.1, 1e-3);
            EXPECT_EQ(dev::light_path(renderer), sampling);
        }
}

TEST_F(Thickness, LightPathAutoFollowsTheMeshResolution)
{
    // Per vertex where the median edge spans at most 8 texels of the light's depth tile
    // (2.2 bounding radii across): the bunny's 0.0046 of the diagonal is 2.1 texels of a 512²
    // tile, the fist's 0.031 is 14; a 4096² tile makes the bunny's 17.
    auto sampling = [&](const char* name, uint32_t tile) {
        const PreparedMesh mesh = prepare_mesh(load_mesh(test::asset(name)));
        Renderer renderer(context(), RendererOptions{.light_depth_size = tile});
        EXPECT_EQ(dev::light_path(renderer), dev::LightPathSampling::PerFragment) << "before set_mesh";
        renderer.set_mesh(mesh);
        return dev::light_path(renderer);
    };
    EXPECT_EQ(sampling("bunny00.off", 512), dev::LightPathSampling::PerVertex);
    EXPECT_EQ(sampling("hand.off", 512), dev::LightPathSampling::PerFragment);
    EXPECT_EQ(sampling("bunny00.off", 4096), dev::LightPathSampling::PerFragment);
    EXPECT_EQ(dev::parse_light_path_sampling("vertex"), dev::LightPathSampling::PerVertex);
    EXPECT_THROW(dev::parse_light_path_sampling("pixel"), Error);
}

TEST_F(Thickness, ExtremeThicknessAndExtinctionStayFinite)
{
    const PreparedMesh slab = prepare_mesh(dev::procedural::box({-1.0f, -1.0f, -0.1f}, {1.0f, 1.0f, 0.1f}, 8));
    Renderer renderer(context());
    Material m = translucent();
    Camera cam;
    cam.eye = {0.0f, 0.0f, 6.0f};
    const std::vector<Light> lights = {Light::directional({0.0f, 0.0f, -1.0f}, glm::vec3(1.0f))};
    RenderSettings rs;
    rs.width = rs.height = 16, rs.float32 = true;
    for (float thickness : {0.0f, 1e-30f, 1.0f, 3e38f})
        for (float sigma : {0.0f, 1e-6f, 1e6f, 3e38f}) {
            renderer.set_mesh(slab, {}, std::vector<float>(slab.vertex_count(), thickness));
            m.transmission.sigma_t = glm::vec3(sigma);
            renderer.set_material(m);
            const RenderedImage img = renderer.render(cam, lights, rs);
            for (size_t i = 0; i < img.rgba.size(); ++i)
                ASSERT_TRUE(std::isfinite(img.rgba[i]))
                    << "thickness " << thickness << ", sigma_t " << sigma << " at " << i << " of " << img.rgba.size();
        }
    EXPECT_THROW(renderer.set_mesh(slab, {}, std::vector<float>(slab.vertex_count(), INFINITY)), Error);
    EXPECT_THROW(renderer.set_mesh(slab, {}, std::vector<float>(slab.vertex_count(), -1.0f)), Error);
}

TEST_F(Thickness, BoundaryTransmittanceIsTheFresnelOfBothCrossings)
{
    // Diffuse light that enters at cos θ_l and leaves at cos θ_v is scaled by
    // T(θ_l)·T(θ_v), T(μ) = 1 − (F0 + (max(1 − α, F0) − F0)(1 − μ)^5): the slab's centre seen
    // head-on (μ_v = 1) under a light at 45°, t_m = 0 and strength 0 (so the rest is Lambert).
    const PreparedMesh slab = prepare_mesh(dev::procedural::box({-5.0f, -5.0f, -0.05f}, {5.0f, 5.0f, 0.05f}, 16));
    Renderer renderer(context());
    renderer.set_mesh(slab);
    Material m = translucent();
    m.specular = 0.0f, m.strength = 0.0f;
    Camera cam;
    cam.eye = {0.0f, 0.0f, 3.0f}, cam.fov_y_degrees = 10.0f;
    const std::vector<Light> lights = {Light::directional({1.0f, 0.0f, 1.0f}, glm::vec3(1.0f))};
    RenderSettings rs;
    rs.width = rs.height = 33, rs.float32 = true;
    renderer.set_material(m);
    const float with = renderer.render(cam, lights, rs).pixel(16, 16)[0];
    m.boundary_transmittance = false;
    renderer.set_material(m);
    const float without = renderer.render(cam, lights, rs).pixel(16, 16)[0];
    const double f0 = std::pow((m.ior - 1.0) / (m.ior + 1.0), 2.0),
                 grazing = std::max(1.0 - double(m.roughness) * m.roughness, f0);
    auto t = [&](double mu) { return 1.0 - (f0 + (grazing - f0) * std::pow(1.0 - mu, 5.0)); };
    EXPECT_NEAR(without, m.albedo.r / std::numbers::pi * std::sqrt(0.5), 2e-3 * without);
    EXPECT_NEAR(with / without, t(std::sqrt(0.5)) * t(1.0), 1e-3);
}
