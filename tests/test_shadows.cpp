// Shadows (RenderSettings::shadows, shaders/include/shadow.glsl) against the geometry: a box over
// a plane under a directional and a point light straight above it (umbra, the lit plane's
// analytic Lambert value, the shadow's centre and width where projection puts them), and a lit
// sphere that must look the same with and without shadows (no acne, the wrap past the
// terminator kept).
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/bake.hpp>
#include <jade/dev/names.hpp>
#include <jade/render.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace jade;
using jade::test::GpuTest;

namespace {

constexpr uint32_t kSize = 192;
constexpr float kAlbedo = 0.8f;

// A slab whose top is the plane z = 0 (x, y ∈ [−3, 3]) and a unit box from z = 2 to 3 above its
// centre: one mesh, so the box shadows the plane.
PreparedMesh plane_and_box()
{
    TriangleMesh mesh;
    mesh.name = "plane and box";
    for (const TriangleMesh& part : {dev::procedural::box({-3.0f, -3.0f, -0.1f}, {3.0f, 3.0f, 0.0f}, 24),
                                     dev::procedural::box({-0.5f, -0.5f, 2.0f}, {0.5f, 0.5f, 3.0f}, 4)}) {
        const uint32_t base = uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
        for (uint32_t i : part.indices) mesh.indices.push_back(base + i);
    }
    return prepare_mesh(mesh);
}

// From the front and above, so that the box hides the plane from y = 1.5 on, not its shadow.
Camera camera()
{
    Camera c;
    c.eye = {0.0f, -7.0f, 7.0f}, c.target = {0.0f, 0.0f, 0.0f}, c.fov_y_degrees = 40.0f;
    c.near_plane = 1.0f, c.far_plane = 30.0f;
    return c;
}

// Pixel coordinates (x right, y down, pixel centres at integers) of a world point.
glm::vec2 project(glm::vec3 p)
{
    const glm::vec4 clip = camera().view_projection(1.0f) * glm::vec4(p, 1.0f);
    return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * float(kSize) - 0.5f;
}

// Where the ray through pixel centre (x, y) meets the plane z = 0.
glm::vec3 on_plane(uint32_t x, uint32_t y)
{
    const glm::mat4 inv = glm::inverse(camera().view_projection(1.0f));
    const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / float(kSize) * 2.0f - 1.0f;
    glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f), b = inv * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 p = glm::vec3(a) / a.w, q = glm::vec3(b) / b.w;
    return p + (q - p) * (-p.z / (q.z - p.z));
}

// The plane and box, lit as a matte grey surface (no specular): only the diffuse term is drawn.
void set_matte_plane_and_box(Renderer& r)
{
    r.set_mesh(plane_and_box());
    Material m = burley_material(glm::dvec3(0.01), glm::vec3(kAlbedo), "matte");
    m.specular = 0.0f;
    r.set_material(m);
}

// The red channel of the pixel nearest to `px`.
float red_at(const RenderedImage& img, glm::vec2 px)
{
    return img.pixel(uint32_t(std::lround(px.x)), uint32_t(std::lround(px.y)))[0];
}

RenderSettings lambert(bool shadows)
{
    RenderSettings s;
    s.width = s.height = kSize, s.mode = ShadingMode::Lambert, s.float32 = true, s.shadows = shadows;
    return s;
}

// The edges of the dark run through `at` along a row (dx = 1) or a column (dy = 1): where the
// red channel crosses half of `lit`, interpolated between pixels.
std::pair<double, double> dark_run(const RenderedImage& img, glm::ivec2 at, glm::ivec2 step, double lit)
{
    auto value = [&](glm::ivec2 p) { return double(img.pixel(uint32_t(p.x), uint32_t(p.y))[0]); };
    auto edge = [&](int sign) {
        glm::ivec2 p = at;
        while (value(p + sign * step) < 0.5 * lit) p += sign * step;
        const double inside = value(p), outside = value(p + sign * step);
        const double f = (0.5 * lit - inside) / (outside - inside);
        const glm::ivec2 d = sign * step;
        return glm::dot(glm::dvec2(p) + f * glm::dvec2(d), glm::dvec2(step));
    };
    return {edge(-1), edge(1)};
}

struct Measured {
    glm::dvec2 centre, size;  // of the shadow, pixels
};

Measured measure(const RenderedImage& img, glm::vec2 centre, double lit)
{
    const glm::ivec2 at(int(std::lround(centre.x)), int(std::lround(centre.y)));
    const auto [x0, x1] = dark_run(img, at, {1, 0}, lit);
    const auto [y0, y1] = dark_run(img, at, {0, 1}, lit);
    return {{0.5 * (x0 + x1), 0.5 * (y0 + y1)}, {x1 - x0, y1 - y0}};
}

}  // namespace

class RenderShadows : public GpuTest {};

TEST_F(RenderShadows, ABoxShadowsThePlaneUnderADirectionalLight)
{
    Renderer r(context());
    set_matte_plane_and_box(r);
    const Light light = Light::directional({0.0f, 0.0f, 1.0f}, glm::vec3(1.0f));
    const RenderedImage img = r.render(camera(), {&light, 1}, lambert(true));
    const RenderedImage bare = r.render(camera(), {&light, 1}, lambert(false));
    const double lit = kAlbedo / std::numbers::pi;  // E = 1 at normal incidence
    // Far from the shadow: the plane's analytic Lambert value, with shadows as without.
    for (glm::vec3 p : {glm::vec3(2.0f, -2.0f, 0.0f), glm::vec3(-2.2f, -1.0f, 0.0f), glm::vec3(2.3f, 0.5f, 0.0f)}) {
        const glm::vec2 px = project(p);
        EXPECT_NEAR(red_at(img, px), lit, 1e-3 * lit) << "at " << p.x << ", " << p.y;
        EXPECT_EQ(red_at(img, px), red_at(bare, px));
    }
    // The umbra: the box's footprint, [−0.5, 0.5]² on the plane; its centre black.
    const glm::vec2 centre = project({0.0f, 0.0f, 0.0f});
    EXPECT_LT(red_at(img, centre), 1e-4 * lit);
    for (glm::vec3 p : {glm::vec3(0.3f, 0.3f, 0.0f), glm::vec3(-0.3f, -0.3f, 0.0f)}) {
        const glm::vec2 px = project(p);
        EXPECT_LT(red_at(img, px), 1e-4 * lit);
    }
    // Its centre and width where the geometry puts them (±2 px; a texel of the tile is 0.45 px).
    const Measured s = measure(img, centre, lit);
    EXPECT_NEAR(s.centre.x, centre.x, 2.0);
    EXPECT_NEAR(s.centre.y, centre.y, 2.0);
    const double width = project({0.5f, 0.0f, 0.0f}).x - project({-0.5f, 0.0f, 0.0f}).x;
    EXPECT_NEAR(s.size.x, width, 2.0) << "projected width " << width;
    const double depth = project({0.0f, -0.5f, 0.0f}).y - project({0.0f, 0.5f, 0.0f}).y;
    EXPECT_NEAR(s.size.y, depth, 2.0) << "projected depth " << depth;
    std::printf("directional: shadow centre (%.2f, %.2f) px, projected (%.2f, %.2f); size %.2f x %.2f px, projected "
                "%.2f x %.2f\n",
                s.centre.x, s.centre.y, centre.x, centre.y, s.size.x, s.size.y, width, depth);
    // Without shadows the plane is lit there.
    EXPECT_NEAR(red_at(bare, centre), lit, 1e-3 * lit);
    // Every lit mode shadows; the false colour does not.
    for (ShadingMode mode : {ShadingMode::Curvature, ShadingMode::Tm}) {
        RenderSettings rs = lambert(true);
        rs.mode = mode;
        const RenderedImage shaded = r.render(camera(), {&light, 1}, rs);
        EXPECT_LT(red_at(shaded, centre), 1e-3 * lit) << dev::shading_mode_name(mode);
    }
}

TEST_F(RenderShadows, AMaterialWithoutAProfileGetsLambertsShadowInTheTmMode)
{
    // Its soft-shadow kernel has no radius of its own and is widened to a texel of the tile: the
    // same shadow as Lambert's filter, to within a pixel (a texel of the tile is 0.45 px). A
    // kernel left at a mesh unit would miss the box altogether.
    Renderer r(context());
    r.set_mesh(plane_and_box());
    Material m = material_preset("opaque", 100.0);
    m.specular = 0.0f;
    r.set_material(m);
    const Light light = Light::directional({0.0f, 0.0f, 1.0f}, glm::vec3(1.0f));
    RenderSettings tm = lambert(true);
    tm.mode = ShadingMode::Tm;
    const RenderedImage flat = r.render(camera(), {&light, 1}, lambert(true));
    const RenderedImage soft = r.render(camera(), {&light, 1}, tm);
    const glm::vec2 centre = project({0.0f, 0.0f, 0.0f});
    const double lit = red_at(soft, project({2.0f, -2.0f, 0.0f}));
    ASSERT_GT(lit, 0.0);
    EXPECT_LT(red_at(soft, centre), 1e-4 * lit);
    const Measured a = measure(flat, centre, red_at(flat, project({2.0f, -2.0f, 0.0f}))),
                   b = measure(soft, centre, lit);
    EXPECT_NEAR(b.centre.x, a.centre.x, 1.0);
    EXPECT_NEAR(b.centre.y, a.centre.y, 1.0);
    EXPECT_NEAR(b.size.x, a.size.x, 1.0);
    EXPECT_NEAR(b.size.y, a.size.y, 1.0);
    std::printf("no profile: tm shadow %.2f x %.2f px at (%.2f, %.2f), lambert %.2f x %.2f at (%.2f, %.2f)\n", b.size.x,
                b.size.y, b.centre.x, b.centre.y, a.size.x, a.size.y, a.centre.x, a.centre.y);
}

TEST_F(RenderShadows, APointLightsShadowGrowsByThePerspectiveRatio)
{
    // A point light on the axis at height H: the box's top corners (z = 3, half-width 0.5) cast the
    // shadow's edge at 0.5 · H / (H − 3) from the axis.
    Renderer r(context());
    set_matte_plane_and_box(r);
    const float height = 8.0f, intensity = 64.0f;
    const Light light = Light::point({0.0f, 0.0f, height}, glm::vec3(intensity));
    const RenderedImage img = r.render(camera(), {&light, 1}, lambert(true));
    // Far from the shadow: E = I cos θ / d², θ from the vertical, at each pixel's point on the plane.
    for (glm::vec3 p : {glm::vec3(2.0f, -2.0f, 0.0f), glm::vec3(-2.2f, -1.0f, 0.0f), glm::vec3(2.3f, 0.5f, 0.0f)}) {
        const glm::vec2 px = project(p);
        const uint32_t x = uint32_t(std::lround(px.x)), y = uint32_t(std::lround(px.y));
        const glm::dvec3 q = on_plane(x, y);
        const double d = glm::length(glm::dvec3(0.0, 0.0, height) - q);
        const double expected = kAlbedo / std::numbers::pi * intensity * (height / d) / (d * d);
        EXPECT_NEAR(img.pixel(x, y)[0], expected, 5e-3 * expected) << "at " << q.x << ", " << q.y;
    }
    const glm::vec2 centre = project({0.0f, 0.0f, 0.0f});
    const double lit = kAlbedo / std::numbers::pi * intensity / (height * height);
    EXPECT_LT(red_at(img, centre), 1e-4 * lit);
    const Measured s = measure(img, centre, lit);
    const float half = 0.5f * height / (height - 3.0f);  // 0.8: 1.6 times the box
    const double width = project({half, 0.0f, 0.0f}).x - project({-half, 0.0f, 0.0f}).x;
    const double box = project({0.5f, 0.0f, 0.0f}).x - project({-0.5f, 0.0f, 0.0f}).x;
    EXPECT_NEAR(s.centre.x, centre.x, 2.0);
    EXPECT_NEAR(s.centre.y, centre.y, 2.0);
    EXPECT_NEAR(s.size.x, width, 2.0) << "projected: shadow " << width << ", box " << box;
    std::printf("point: shadow centre (%.2f, %.2f) px, projected (%.2f, %.2f); width %.2f px, projected %.2f (the "
                "box %.2f)\n",
                s.centre.x, s.centre.y, centre.x, centre.y, s.size.x, width, box);
}

TEST_F(RenderShadows, ALitSphereHasNoAcne)
{
    // A sphere shadows nothing but itself: with shadows every pixel stays as it is without, on the
    // lit side (no acne) and, in the modes whose light wraps past the terminator, beyond it.
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(1.0f, 96, 192));
    Material m = material_preset("jade", 100.0 / 3.46);
    Baker baker(context());
    const BakeResult bake = baker.bake(sphere, m, BakeSettings::preset(Quality::Draft));
    Renderer r(context());
    r.set_mesh(sphere, bake);
    r.set_material(m);
    Camera cam;
    cam.eye = {0.0f, 0.0f, 5.0f}, cam.fov_y_degrees = 30.0f;
    for (const Light& light :
         {Light::directional({1.0f, 1.0f, 1.0f}, glm::vec3(1.0f)),
          Light::directional({1.0f, 0.2f, -0.1f}, glm::vec3(1.0f)), Light::point({3.0f, 2.0f, 3.0f}, glm::vec3(20.0f))})
        for (ShadingMode mode : {ShadingMode::Lambert, ShadingMode::Curvature, ShadingMode::Tm}) {
            SCOPED_TRACE(std::string(dev::shading_mode_name(mode)) + ", light at " + std::to_string(light.vector.x) +
                         ", " + std::to_string(light.vector.y) + ", " + std::to_string(light.vector.z));
            RenderSettings rs = lambert(true);
            rs.mode = mode, rs.width = rs.height = 128;
            const RenderedImage with = r.render(cam, {&light, 1}, rs);
            rs.shadows = false;
            const RenderedImage without = r.render(cam, {&light, 1}, rs);
            float peak = 0.0f, worst = 0.0f;
            for (size_t i = 0; i < with.rgba.size(); ++i) peak = std::max(peak, without.rgba[i]);
            size_t differ = 0;
            for (size_t i = 0; i < with.rgba.size(); ++i) {
                const float d = std::abs(with.rgba[i] - without.rgba[i]);
                worst = std::max(worst, d);
                differ += d > 1e-3f * peak ? 1 : 0;
            }
            EXPECT_LE(worst, 1e-3f * peak) << differ << " values differ by more than 1e-3 of the peak " << peak;
            std::printf("%s: largest difference %.2e of the peak\n", dev::shading_mode_name(mode).data(), worst / peak);
        }
}
