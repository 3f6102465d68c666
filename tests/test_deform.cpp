// Deformation (jade/deform.hpp): the GPU deformers and the normals/areas pass against float64
// CPU implementations written independently here, glTF animation sampling against values
// computed by hand from tests/data/skinned_morph_anim.gltf, and the glTF loader's checks.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include "../engine/src/deform/animation.hpp"  // deform::sample: the channels one by one

#include <jade/deform.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/mesh.hpp>
#include <jade/bake.hpp>
#include <jade/render.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/norm.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace jade {
namespace {

using test::GpuTest;
constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------ float64 reference: geometry --

struct Reference {
    std::vector<glm::dvec3> positions, normals;
    std::vector<double> areas;
};

/// Area-weighted normals and vertex areas as defined in jade/mesh.hpp (prepare_mesh), float64.
void normals_and_areas(const std::vector<uint32_t>& indices, Reference& r)
{
    const size_t n = r.positions.size();
    std::vector<glm::dvec3> sum(n, glm::dvec3(0.0)), largest_normal(n, glm::dvec3(0.0));
    std::vector<double> largest(n, 0.0);
    r.areas.assign(n, 0.0);
    for (size_t t = 0; t < indices.size(); t += 3) {
        const glm::dvec3 a = r.positions[indices[t]], b = r.positions[indices[t + 1]], c = r.positions[indices[t + 2]];
        const glm::dvec3 cr = glm::cross(b - a, c - a);
        const double area = 0.5 * glm::length(cr);
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = indices[t + size_t(k)];
            sum[v] += cr;
            r.areas[v] += area / 3.0;
            if (area > largest[v]) largest[v] = area, largest_normal[v] = cr;
        }
    }
    r.normals.resize(n);
    for (size_t v = 0; v < n; ++v) {
        glm::dvec3 s = sum[v];
        if (!(glm::length(s) > 1e-9 * 6.0 * r.areas[v])) s = largest_normal[v];
        r.normals[v] = glm::length(s) > 0.0 ? s / glm::length(s) : glm::dvec3(0, 0, 1);
    }
}

/// The procedural deformers in float64, written from their geometric definitions (not from the
/// shader's formulas): the bend maps the axis onto a circular arc of radius 1/κ.
glm::dvec3 deform_reference(const ProceduralDeformer& d, double t, glm::dvec3 p)
{
    const int a = int(d.axis), u = (a + 1) % 3, v = (a + 2) % 3;
    const glm::dvec3 o(d.origin);
    const double s = std::sin(2.0 * kPi * t / d.period);
    double h = p[a] - o[a], yu = p[u] - o[u], yv = p[v] - o[v];
    switch (d.kind) {
    case DeformerKind::Bend: {
        const double kappa = d.amplitude * s / d.length;
        if (kappa != 0.0) {
            // Centre of curvature on the v side at distance R from the axis; a point at height h
            // and offset yv sits at radius R − yv, angle κh.
            const double radius = 1.0 / kappa, angle = kappa * h;
            const double nh = (radius - yv) * std::sin(angle);
            const double nv = radius - (radius - yv) * std::cos(angle);
            h = nh, yv = nv;
        }
        break;
    }
    case DeformerKind::Twist: {
        const double phi = d.amplitude * s * h / d.length;
        const double nu = std::cos(phi) * yu - std::sin(phi) * yv, nv = std::sin(phi) * yu + std::cos(phi) * yv;
        yu = nu, yv = nv;
        break;
    }
    case DeformerKind::Squash: {
        const double sigma = 1.0 + d.amplitude * s;
        h *= sigma, yu /= std::sqrt(sigma), yv /= std::sqrt(sigma);
        break;
    }
    case DeformerKind::Wave: yv += d.amplitude * std::sin(2.0 * kPi * (h / d.wavelength - t / d.period)); break;
    }
    glm::dvec3 out;
    out[a] = h, out[u] = yu, out[v] = yv;
    return o + out;
}

/// Signed volume enclosed by a closed mesh (divergence theorem), float64.
double enclosed_volume(const std::vector<glm::dvec3>& p, const std::vector<uint32_t>& idx)
{
    double vol = 0.0;
    for (size_t t = 0; t < idx.size(); t += 3)
        vol += glm::dot(p[idx[t]], glm::cross(p[idx[t + 1]], p[idx[t + 2]])) / 6.0;
    return vol;
}

struct Errors {
    double position = 0, area_rel = 0, normal_max = 0, normal_p999 = 0;
};

/// GPU result against the float64 reference: max position error (mesh units), max relative
/// area error, max and 99.9th percentile normal angle (rad).
Errors compare(const DeformedVertices& gpu, const Reference& ref)
{
    Errors e;
    std::vector<double> angles;
    for (size_t v = 0; v < ref.positions.size(); ++v) {
        e.position = std::max(e.position, glm::length(glm::dvec3(gpu.positions[v]) - ref.positions[v]));
        e.area_rel = std::max(e.area_rel, std::abs(double(gpu.areas[v]) - ref.areas[v]) / ref.areas[v]);
        const double c = std::clamp(
            glm::dot(glm::dvec3(gpu.normals[v]), ref.normals[v]) / glm::length(glm::dvec3(gpu.normals[v])), -1.0, 1.0);
        angles.push_back(std::acos(c));
    }
    std::sort(angles.begin(), angles.end());
    e.normal_max = angles.back();
    e.normal_p999 = angles[size_t(0.999 * double(angles.size() - 1))];
    return e;
}

// ------------------------------------------------------------------------ procedural, GPU --

class DeformGpu : public GpuTest {};

struct Case {
    const char* mesh;  // "bunny" or "box"
    DeformerKind kind;
    uint32_t axis;
};

PreparedMesh load_case_mesh(const std::string& which)
{
    if (which == "bunny") return prepare_mesh(load_mesh(test::asset("bunny00.off")));
    return prepare_mesh(dev::procedural::box({-0.3f, 0.0f, -0.2f}, {0.3f, 2.0f, 0.2f}, 12));
}

TEST_F(DeformGpu, ProceduralDeformersMatchFloat64OnSeveralFrames)
{
    for (const char* which : {"box", "bunny"}) {
        const PreparedMesh rest = load_case_mesh(which);
        MeshDeformer deformer(context(), rest);
        for (DeformerKind kind : {DeformerKind::Bend, DeformerKind::Twist, DeformerKind::Squash, DeformerKind::Wave}) {
            for (uint32_t axis : {0u, 1u, 2u}) {
                ProceduralDeformer d = ProceduralDeformer::fit(kind, rest, axis);
                for (double t : {0.0, 0.3, 0.85, 1.55}) {
                    SCOPED_TRACE(std::string(which) + " " + std::string(dev::deformer_name(kind)) + " axis " +
                                 std::to_string(axis) + " t " + std::to_string(t));
                    const DeformTimings timings = deformer.deform(d, t);
                    EXPECT_GE(timings.deform_ms, 0.0);
                    const DeformedVertices gpu = deformer.read();
                    Reference ref;
                    for (const auto& p : rest.positions) ref.positions.push_back(deform_reference(d, t, glm::dvec3(p)));
                    normals_and_areas(rest.indices, ref);
                    const Errors e = compare(gpu, ref);
                    // float32 trigonometry on coordinates of size ~diagonal: a few ulps of the
                    // diagonal (measured ≤ 1.1e-7); areas and normals of the bunny's small
                    // triangles from float32 positions: measured ≤ 5.4e-5 and ≤ 4.7e-5 rad.
                    EXPECT_LT(e.position, 5e-7 * rest.diagonal);
                    EXPECT_LT(e.area_rel, 2e-4);
                    EXPECT_LT(e.normal_p999, 1e-4);
                    EXPECT_LT(e.normal_max, 2e-4);
                }
            }
        }
    }
}

// The GPU-resident frame: deform, re-bake and draw without mesh data through the host
// (Renderer::update_vertices from the deformer's and the re-bake's buffers) renders the same
// image as handing the read-back deformed mesh and bake to set_mesh: t_m, the thickness, and the
// scattering normals and spreads the renderer derives from the per-channel normal sums.
TEST_F(DeformGpu, GpuVertexUpdateRendersLikeTheHostPath)
{
    const PreparedMesh rest = load_case_mesh("box");
    MeshDeformer deformer(context(), rest);
    const ProceduralDeformer bend = ProceduralDeformer::fit(DeformerKind::Bend, rest, 1);
    deformer.deform(bend, 0.5);
    // A coloured medium a few mean free paths across the box: t_m, spreads and thickness all matter.
    Medium medium;
    medium.sigma_s = glm::dvec3(4.0, 8.0, 16.0) / double(rest.diagonal),
    medium.sigma_a = glm::dvec3(0.5 / rest.diagonal);
    Material material = Material::from_medium(medium);
    // The diffused transmission gathers over the whole light depth tile, which sits about the
    // bounds set_mesh saw (the rest pose's in the GPU path, the deformed pose's in the host path):
    // its taps fall on other texels in the two (0.14 apart at this size). It has its own tests
    // (tests/test_thickness.cpp); this one is about the vertices.
    material.transmission.diffusion_weight = 0.0f;
    Baker baker(context());
    DynamicBake rebake(baker, rest, material, BakeSettings::preset(Quality::Draft));
    const BakeResult baked =
        rebake.bake(deformer.buffers().positions, deformer.buffers().normals, deformer.buffers().areas);

    Camera camera = Camera::framing(rest.bbox_min - glm::vec3(0.5f), rest.bbox_max + glm::vec3(0.5f));
    camera.near_plane = 0.1f, camera.far_plane = 50.0f;  // the same planes for both paths
    const auto lights = figure1_lights(camera);
    RenderSettings settings;
    settings.width = settings.height = 96;
    // Shadows come from the same tiles, per fragment, so their edges land on other texels in the
    // two paths (0.009 apart at this size): this test is about the vertices.
    settings.shadows = false;

    // Light paths read per vertex: per fragment they come from a depth tile placed about the
    // bounds set_mesh saw, the rest pose's here and the deformed pose's in the host path, so
    // the two tiles' texels differ (by up to ~0.01 at this size).
    RendererOptions options;
    dev::set_study(options, {.light_path = dev::LightPathSampling::PerVertex});
    Renderer gpu_path(context(), options);
    gpu_path.set_material(material);
    gpu_path.set_mesh(rest);
    const RenderedImage before = gpu_path.render(camera, lights, settings);
    gpu_path.update_vertices(deformer.buffers().positions, deformer.buffers().normals, rebake.buffers().tm,
                             rebake.buffers().thickness, rebake.buffers().scattering_normal);
    const RenderedImage gpu_image = gpu_path.render(camera, lights, settings);

    Renderer host_path(context(), options);
    host_path.set_material(material);
    ASSERT_FALSE(baked.thickness.empty());
    ASSERT_FALSE(baked.normal_spread.empty());
    host_path.set_mesh(deformed_mesh(rest, deformer.read()), baked);
    const RenderedImage host_image = host_path.render(camera, lights, settings);

    float worst = 0, moved = 0;
    for (size_t i = 0; i < host_image.rgba.size(); ++i) {
        worst = std::max(worst, std::abs(gpu_image.rgba[i] - host_image.rgba[i]));
        moved = std::max(moved, std::abs(gpu_image.rgba[i] - before.rgba[i]));
    }
    EXPECT_LE(worst, 1e-3f) << "GPU-updated vertices against the host path (RGBA16F target)";
    EXPECT_GT(moved, 0.1f) << "the update must change the picture";
    EXPECT_THROW(gpu_path.update_vertices(VK_NULL_HANDLE, deformer.buffers().normals, rebake.buffers().tm), Error);
}

TEST_F(DeformGpu, NormalsAndAreasMatchPrepareMeshOfTheDeformedPositions)
{
    // The definition check: prepare_mesh (float64 from the same float positions) on the GPU's
    // deformed positions gives the GPU's normals and areas.
    const PreparedMesh rest = load_case_mesh("bunny");
    MeshDeformer deformer(context(), rest);
    deformer.deform(ProceduralDeformer::fit(DeformerKind::Twist, rest, 1), 0.4);
    const DeformedVertices gpu = deformer.read();
    TriangleMesh deformed;
    deformed.name = "deformed bunny";
    deformed.positions = gpu.positions;
    deformed.indices = rest.indices;
    const PreparedMesh cpu = prepare_mesh(deformed);
    ASSERT_EQ(cpu.vertex_count(), rest.vertex_count());
    double area_err = 0.0, normal_err = 0.0;
    for (size_t v = 0; v < rest.vertex_count(); ++v) {
        area_err = std::max(area_err, std::abs(double(gpu.areas[v]) - cpu.areas[v]) / cpu.areas[v]);
        normal_err = std::max(normal_err, double(glm::length(gpu.normals[v] - cpu.normals[v])));
    }
    EXPECT_LT(area_err, 2e-4);
    EXPECT_LT(normal_err, 2e-4);
    // deformed_mesh keeps the triangles and recomputes the bounds.
    const PreparedMesh dm = deformed_mesh(rest, gpu);
    EXPECT_EQ(dm.indices, rest.indices);
    EXPECT_NEAR(dm.diagonal, cpu.diagonal, 1e-6 * cpu.diagonal);
}

TEST_F(DeformGpu, SquashPreservesVolumeAndBendPreservesAxisLength)
{
    const PreparedMesh rest = prepare_mesh(procedural::sphere(1.0f, 48, 96));
    MeshDeformer deformer(context(), rest);
    std::vector<glm::dvec3> p0(rest.positions.begin(), rest.positions.end());
    const double v0 = enclosed_volume(p0, rest.indices);
    ProceduralDeformer squash = ProceduralDeformer::fit(DeformerKind::Squash, rest, 1);
    squash.amplitude = 0.5f;
    deformer.deform(squash, 0.5);  // s = 1: stretched by 1.5 along y
    const auto gpu = deformer.read();
    std::vector<glm::dvec3> p1(gpu.positions.begin(), gpu.positions.end());
    EXPECT_NEAR(enclosed_volume(p1, rest.indices) / v0, 1.0, 1e-5);
    double highest = -1e9;
    for (const auto& p : gpu.positions) highest = std::max(highest, double(p.y));
    EXPECT_NEAR(highest, -1.0 + 2.0 * 1.5, 1e-5);  // base at y = -1 stays, height 2 → 3

    // A thin bent grid: the distance along the arc from the base to the top stays the length.
    TriangleMesh strip = dev::procedural::grid(40, 0.05f);  // z = 0 plane, x, y in [-1, 1]
    const PreparedMesh flat = prepare_mesh(strip);
    MeshDeformer bend_deformer(context(), flat);
    ProceduralDeformer bend = ProceduralDeformer::fit(DeformerKind::Bend, flat, 1);
    bend.axis = 1;
    bend.amplitude = float(kPi / 2);  // the top ends at 90°
    bend_deformer.deform(bend, 0.5);  // s(t) = sin(π/2) = 1
    const auto bent = bend_deformer.read();
    // The axis line (x = 0 in the grid; v = x for axis y) maps to a quarter circle of radius
    // 2/(π/2): its top vertex goes to (R, R) in (h, v).
    const double radius = 2.0 / (kPi / 2);
    size_t top = 0;
    for (size_t v = 0; v < flat.vertex_count(); ++v)
        if (glm::distance(flat.positions[v], glm::vec3(0, 1, 0)) <
            glm::distance(flat.positions[top], glm::vec3(0, 1, 0)))
            top = v;
    ASSERT_LT(glm::distance(flat.positions[top], glm::vec3(0, 1, 0)), 1e-6f);
    EXPECT_NEAR(bent.positions[top].y - flat.bbox_min.y, radius, 1e-5);
    EXPECT_NEAR(bent.positions[top].x, radius, 1e-5);
}

TEST_F(DeformGpu, TwoSidedSheetTakesTheLargestTrianglesNormal)
{
    // Each triangle of a grid also listed reversed: at every vertex the cross products cancel
    // exactly, and prepare_mesh's rule picks the largest adjacent triangle, the first one on
    // ties — here the front side (listed first), so after a wave every normal faces +z-ish.
    TriangleMesh sheet = dev::procedural::grid(16, 0.1f);
    const size_t front = sheet.indices.size();
    for (size_t t = 0; t < front; t += 3)
        sheet.indices.insert(sheet.indices.end(), {sheet.indices[t], sheet.indices[t + 2], sheet.indices[t + 1]});
    const PreparedMesh rest = prepare_mesh(sheet);
    MeshDeformer deformer(context(), rest);
    ProceduralDeformer wave = ProceduralDeformer::fit(DeformerKind::Wave, rest, 0);  // displaces along v = z
    wave.amplitude = 0.1f;
    deformer.deform(wave, 0.3);
    const DeformedVertices gpu = deformer.read();
    Reference ref;
    for (const auto& p : rest.positions) ref.positions.push_back(deform_reference(wave, 0.3, glm::dvec3(p)));
    normals_and_areas(rest.indices, ref);
    const Errors e = compare(gpu, ref);
    EXPECT_LT(e.normal_max, 1e-5);
    for (const auto& n : gpu.normals) EXPECT_GT(n.z, 0.5f);
    EXPECT_LT(e.area_rel, 1e-5);
}

TEST_F(DeformGpu, RejectsBadParameters)
{
    const PreparedMesh rest = load_case_mesh("box");
    MeshDeformer deformer(context(), rest);
    ProceduralDeformer d = ProceduralDeformer::fit(DeformerKind::Squash, rest, 1);
    d.amplitude = 1.0f;
    EXPECT_THROW(deformer.deform(d, 0.1), Error);
    d = ProceduralDeformer::fit(DeformerKind::Wave, rest, 1);
    d.wavelength = 0.0f;
    EXPECT_THROW(deformer.deform(d, 0.1), Error);
    d.wavelength = 1.0f;
    d.axis = 3;
    EXPECT_THROW(deformer.deform(d, 0.1), Error);
    EXPECT_THROW(deformer.deform(Pose{}), Error);  // no skin set
    EXPECT_THROW(dev::parse_deformer("spin"), Error);
    EXPECT_EQ(dev::parse_deformer("twist"), DeformerKind::Twist);
}

// ------------------------------------------------------------------ glTF animation, CPU side --

AnimatedMesh load_test_asset() { return load_animated_gltf(test::data("skinned_morph_anim.gltf")); }

const AnimationChannel& channel(const AnimatedMesh& m, AnimationPath path)
{
    for (const auto& c : m.animations.at(0).channels)
        if (c.path == path) return c;
    throw Error("no channel");
}

TEST(DeformAnimation, LoadsSkinMorphTargetsAndChannels)
{
    const AnimatedMesh m = load_test_asset();
    EXPECT_EQ(m.mesh.positions.size(), 20u);
    EXPECT_EQ(m.mesh.triangle_count(), 36u);
    EXPECT_EQ(m.mesh_node, 0);
    ASSERT_TRUE(m.skinned);
    EXPECT_EQ(m.joints, (std::vector<int>{1, 2}));
    EXPECT_FLOAT_EQ(m.inverse_bind[1][3][1], -1.0f);
    ASSERT_EQ(m.morph_deltas.size(), 1u);
    EXPECT_FLOAT_EQ(m.morph_deltas[0][16].x, -0.025f);  // top ring, corner (-0.25, 2, -0.25)
    EXPECT_EQ(m.nodes[2].parent, 1);
    ASSERT_EQ(m.animations.size(), 1u);
    EXPECT_EQ(m.animations[0].channels.size(), 3u);
    EXPECT_DOUBLE_EQ(m.animations[0].duration(), 1.0);
    EXPECT_EQ(m.joint_weights[8], glm::vec4(0.5f, 0.5f, 0.0f, 0.0f));  // ring y = 1
}

TEST(DeformAnimation, LinearRotationIsSlerpAtKeysAndBetween)
{
    const AnimatedMesh mesh = load_test_asset();
    const AnimationChannel& c = channel(mesh, AnimationPath::Rotation);
    EXPECT_EQ(c.interpolation, Interpolation::Linear);
    auto expect_angle = [&](double t, double degrees) {
        const auto q = deform::sample(c, t);  // about z: (0, 0, sin(α/2), cos(α/2))
        const double half = degrees * kPi / 360.0;
        EXPECT_NEAR(q[0], 0.0, 1e-7);
        EXPECT_NEAR(q[1], 0.0, 1e-7);
        EXPECT_NEAR(q[2], std::sin(half), 1e-6) << "t = " << t;
        EXPECT_NEAR(q[3], std::cos(half), 1e-6) << "t = " << t;
    };
    expect_angle(-1.0, 0.0);  // clamped before the first key
    expect_angle(0.0, 0.0);
    expect_angle(0.25, 22.5);  // slerp: the angle is linear in t (nlerp would give 21.7°)
    expect_angle(0.5, 45.0);
    expect_angle(1.0, 90.0);
    expect_angle(3.0, 90.0);
}

TEST(DeformAnimation, StepHoldsTheKeyAtOrBefore)
{
    const AnimatedMesh mesh = load_test_asset();
    const AnimationChannel& c = channel(mesh, AnimationPath::Translation);
    EXPECT_EQ(c.interpolation, Interpolation::Step);
    EXPECT_EQ(deform::sample(c, 0.0), (std::vector<float>{0, 0, 0}));
    EXPECT_EQ(deform::sample(c, 0.49), (std::vector<float>{0, 0, 0}));
    EXPECT_EQ(deform::sample(c, 0.5), (std::vector<float>{1, 0, 0}));
    EXPECT_EQ(deform::sample(c, 0.75), (std::vector<float>{1, 0, 0}));
    EXPECT_EQ(deform::sample(c, 1.0), (std::vector<float>{2, 0, 0}));
}

TEST(DeformAnimation, CubicSplineIsHermiteWithScaledTangents)
{
    const AnimatedMesh mesh = load_test_asset();
    const AnimationChannel& c = channel(mesh, AnimationPath::Weights);
    EXPECT_EQ(c.interpolation, Interpolation::CubicSpline);
    // p(s) = (2s³−3s²+1)·0 + (s³−2s²+s)·1·2 + (−2s³+3s²)·1 + (s³−s²)·1·0
    auto expected = [](double s) { return 2.0 * (s * s * s - 2 * s * s + s) + (-2 * s * s * s + 3 * s * s); };
    for (double t : {0.0, 0.25, 0.5, 0.9, 1.0}) EXPECT_NEAR(deform::sample(c, t)[0], expected(t), 1e-6) << "t = " << t;
    EXPECT_NEAR(deform::sample(c, 0.5)[0], 0.75, 1e-6);
    EXPECT_NEAR(deform::sample(c, 0.25)[0], 0.4375, 1e-6);
}

/// The joint matrices of the test asset at time t, by hand (see make_test_data.py).
std::vector<glm::dmat4> expected_joints(double t)
{
    const double x = t < 0.5 ? 0.0 : (t < 1.0 ? 1.0 : 2.0);
    const double angle = std::clamp(t, 0.0, 1.0) * kPi / 2;
    const glm::dmat4 root = glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0, 0));
    const glm::dmat4 upper = root * glm::translate(glm::dmat4(1.0), glm::dvec3(0, 1, 0)) *
                             glm::rotate(glm::dmat4(1.0), angle, glm::dvec3(0, 0, 1));
    return {root, upper * glm::translate(glm::dmat4(1.0), glm::dvec3(0, -1, 0))};
}

TEST(DeformAnimation, PoseJointMatricesAndMorphWeights)
{
    const AnimatedMesh m = load_test_asset();
    for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        const Pose pose = evaluate_pose(m, 0, t);
        const auto want = expected_joints(t);
        ASSERT_EQ(pose.joint_matrices.size(), 2u);
        for (int j = 0; j < 2; ++j)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(pose.joint_matrices[size_t(j)][c][r], want[size_t(j)][c][r], 1e-6)
                        << "t " << t << " joint " << j;
        ASSERT_EQ(pose.morph_weights.size(), 1u);
        EXPECT_NEAR(pose.morph_weights[0], 2.0 * (t * t * t - 2 * t * t + t) + (-2 * t * t * t + 3 * t * t), 1e-6);
    }
}

TEST(DeformAnimation, BadFilesAreErrorsNamingTheElement)
{
    auto expect_error = [](const std::string& file, const std::string& message) {
        try {
            load_animated_gltf(test::data("bad_animation/" + file));
            ADD_FAILURE() << "no error for " << file;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    };
    expect_error("anim_bad_interpolation.gltf", "interpolation 'SMOOTH'");
    expect_error("anim_bad_joint.gltf", "joint node 7 does not exist");
    expect_error("anim_cycle.gltf", "own ancestor");
    expect_error("anim_bad_target.gltf", "target node 9 does not exist");
    expect_error("anim_output_count.gltf", "9 output values for 2 keys, expected 6");
    EXPECT_THROW(load_animated_gltf(test::data("cube.obj")), Error);
}

// ------------------------------------------------------------------ glTF skinning, GPU --

TEST_F(DeformGpu, SkinnedMorphedAnimationMatchesFloat64)
{
    AnimatedMesh m = load_test_asset();
    m.nodes[size_t(m.mesh_node)].translation = glm::vec3(5.0f, 0.0f, 0.0f);  // ignored: the mesh is skinned
    const PreparedMesh rest = prepare_mesh(m.mesh);
    ASSERT_EQ(rest.vertex_count(), 20u);
    MeshDeformer deformer(context(), rest);
    deformer.set_skin(bind_skin(m, rest));
    for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        SCOPED_TRACE("t = " + std::to_string(t));
        deformer.deform(evaluate_pose(m, 0, t));
        const DeformedVertices gpu = deformer.read();
        // By hand: morph with the cubic weight, then blend the two joints (node 0's
        // translation (5, 0, 0) must not appear).
        const double w = 2.0 * (t * t * t - 2 * t * t + t) + (-2 * t * t * t + 3 * t * t);
        const auto joints = expected_joints(t);
        Reference ref;
        for (size_t r = 0; r < m.mesh.positions.size(); ++r) {
            const glm::dvec3 p(m.mesh.positions[r]);
            const glm::dvec3 morphed = p.y == 2.0 ? p + w * glm::dvec3(0.1 * p.x, 0, 0.1 * p.z) : p;
            const double w1 = p.y <= 0.5 ? 0.0 : (p.y == 1.0 ? 0.5 : 1.0);
            const glm::dvec4 h(morphed, 1.0);
            ref.positions.push_back(glm::dvec3((1.0 - w1) * (joints[0] * h) + w1 * (joints[1] * h)));
        }
        normals_and_areas(rest.indices, ref);
        const Errors e = compare(gpu, ref);
        EXPECT_LT(e.position, 1e-6);
        EXPECT_LT(e.area_rel, 1e-5);
        EXPECT_LT(e.normal_max, 1e-5);
    }
    // At t = 1 the top (joint 1 only) is turned by 90° about z around (x, 1, 0) with x = 2:
    // the top centre (0, 2, 0) widened goes to (2 − 1, 1, 0).
    const auto gpu = deformer.read();
    glm::dvec3 centre(0.0);
    for (size_t v = 16; v < 20; ++v) centre += glm::dvec3(gpu.positions[v]) / 4.0;
    EXPECT_NEAR(centre.x, 1.0, 1e-6);
    EXPECT_NEAR(centre.y, 1.0, 1e-6);
}

TEST_F(DeformGpu, UnskinnedMeshFollowsItsNode)
{
    // An unskinned mesh uses its node's world matrix as the one joint.
    AnimatedMesh m = load_test_asset();
    m.nodes[size_t(m.mesh_node)].translation = glm::vec3(5.0f, 0.0f, 0.0f);
    m.skinned = false;
    m.joints.clear();
    m.inverse_bind.clear();
    const PreparedMesh rest = prepare_mesh(m.mesh);
    MeshDeformer deformer(context(), rest);
    deformer.set_skin(bind_skin(m, rest));
    deformer.deform(evaluate_pose(m, 0, 0.0));
    const auto gpu = deformer.read();
    for (size_t v = 0; v < rest.vertex_count(); ++v)
        EXPECT_NEAR(gpu.positions[v].x, rest.positions[v].x + 5.0f, 1e-6);  // node 0's translation
}

}  // namespace
}  // namespace jade
