// Tests of jade::load_mesh on good files (OFF, PLY, OBJ, glTF, GLB), of save_baked_gltf (round
// trip, atomicity, errors) and of save_image (values read back with OpenImageIO).
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/mesh.hpp>
#include <jade/dev/mesh.hpp>

#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

namespace {

using jade::test::asset;
using jade::test::closed_and_oriented;
using jade::test::data;
using jade::test::error_of;
using jade::test::out;

std::string read_bytes(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_vec3_near(glm::vec3 actual, glm::vec3 expected, float tolerance, const std::string& what = "")
{
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

/// Geometric normals of all triangles point away from `centre`.
void expect_outward(const jade::TriangleMesh& m, glm::vec3 centre)
{
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                        c = m.positions[m.indices[3 * t + 2]];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre), 0.0f) << m.name << " triangle " << t;
    }
}

/// A mesh without duplicate positions or degenerate triangles: preparation keeps every vertex
/// and triangle of it.
void expect_prepared_whole(const jade::TriangleMesh& mesh, const jade::PreparedMesh& p)
{
    EXPECT_EQ(p.vertex_count(), mesh.positions.size()) << mesh.name;
    EXPECT_EQ(p.triangle_count(), mesh.triangle_count()) << mesh.name;
    EXPECT_EQ(p.welded_vertices, 0u) << mesh.name;
    EXPECT_EQ(p.dropped_triangles, 0u) << mesh.name;
    EXPECT_EQ(p.unused_vertices, 0u) << mesh.name;
}

/// The unit cube [0, 1]³ of the small test files: its triangles face outwards and, prepared, it
/// is a closed and consistently oriented surface of area 6.
void expect_unit_cube_surface(const jade::TriangleMesh& mesh)
{
    expect_outward(mesh, glm::vec3(0.5f));
    const auto p = jade::prepare_mesh(mesh);
    EXPECT_FLOAT_EQ(jade::dev::total_area(p), 6.0f) << mesh.name;
    EXPECT_TRUE(closed_and_oriented(p)) << mesh.name;
}

// ------------------------------------------------------------------------------ test assets --

TEST(io_load_off, BunnyLoadsWithAllVerticesAndTriangles)
{
    const auto mesh = jade::load_mesh(asset("bunny00.off"));
    EXPECT_EQ(mesh.name, "bunny00.off");
    ASSERT_EQ(mesh.positions.size(), 37706u);
    EXPECT_EQ(mesh.triangle_count(), 75408u);
    EXPECT_EQ(mesh.positions[0], glm::vec3(-0.167662f, -0.411917f, -0.0732205f));  // first vertex line

    const auto p = jade::prepare_mesh(mesh);
    expect_prepared_whole(mesh, p);
    EXPECT_EQ(p.indices, mesh.indices);
    EXPECT_EQ(p.bbox_min, glm::vec3(-0.498959f, -0.493434f, -0.38649f));
    EXPECT_EQ(p.bbox_max, glm::vec3(0.49922f, 0.493767f, 0.386086f));
    EXPECT_NEAR(p.diagonal, 1.602436f, 1e-6f);
    EXPECT_NEAR(jade::dev::total_area(p), 2.354300f, 1e-6f);
    double area_sum = 0.0;
    for (float a : p.areas) area_sum += a;
    EXPECT_NEAR(area_sum, jade::dev::total_area(p), 1e-6 * jade::dev::total_area(p));
    for (const auto& n : p.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST(io_load_off, DragonLoadsWithTenThousandVertices)
{
    const auto mesh = jade::load_mesh(asset("ChineseDragon-10kv.off"));
    ASSERT_EQ(mesh.positions.size(), 10000u);
    EXPECT_EQ(mesh.triangle_count(), 19994u);  // 19994 faces in the header, all triangles
    const auto p = jade::prepare_mesh(mesh);
    expect_prepared_whole(mesh, p);
    EXPECT_EQ(p.bbox_min, glm::vec3(-34.4333076f, -52.6971169f, -1036.63074f));
    EXPECT_EQ(p.bbox_max, glm::vec3(27.1646004f, 60.1910858f, -927.312439f));
    EXPECT_NEAR(p.diagonal, 168.7855f, 1e-3f);
}

// ------------------------------------------------------------------------------ small files --

TEST(io_load_off, ColouredQuadsAreFanTriangulated)
{
    const auto mesh = jade::load_mesh(data("cube_colors.off"));
    EXPECT_EQ(mesh.positions.size(), 8u);
    EXPECT_EQ(mesh.triangle_count(), 12u);
    EXPECT_TRUE(mesh.normals.empty());
    // Face "4 0 4 6 2" becomes (0 4 6) (0 6 2).
    EXPECT_EQ(std::vector<uint32_t>(mesh.indices.begin(), mesh.indices.begin() + 6),
              (std::vector<uint32_t>{0, 4, 6, 0, 6, 2}));
    EXPECT_EQ(mesh.positions[7], glm::vec3(1, 1, 1));
    expect_unit_cube_surface(mesh);
}

TEST(io_load_off, NoffNormalsAreRead)
{
    const auto mesh = jade::load_mesh(data("tetra_normals.off"));
    ASSERT_EQ(mesh.normals.size(), 4u);
    expect_vec3_near(mesh.normals[1], glm::vec3(1, -1, -1) / std::sqrt(3.0f), 1e-6f);
    const auto p = jade::prepare_mesh(mesh);
    EXPECT_NEAR(jade::dev::total_area(p), 8.0f * std::sqrt(3.0f), 1e-5f);
    EXPECT_TRUE(closed_and_oriented(p));
    expect_outward(mesh, glm::vec3(0.0f));
}

TEST(io_load_off, ExtensionIsCaseInsensitive)
{
    const auto copy = out("loaders/CUBE.OFF");
    std::filesystem::copy_file(data("cube_colors.off"), copy);
    EXPECT_EQ(jade::load_mesh(copy).triangle_count(), 12u);
}

TEST(io_load_ply, AsciiAndBinaryBothEndiannessesGiveTheSameMesh)
{
    // The three files differ in list count/index types, the list name (vertex_index), and element
    // order (faces first in the big-endian file); all have properties and an element to skip.
    const auto ascii = jade::load_mesh(data("cube_ascii.ply"));
    const auto little = jade::load_mesh(data("cube_binary_le.ply"));
    const auto big = jade::load_mesh(data("cube_binary_be.ply"));
    ASSERT_EQ(ascii.positions.size(), 8u);
    EXPECT_EQ(ascii.triangle_count(), 12u);
    for (const auto* m : {&little, &big}) {
        EXPECT_EQ(m->positions, ascii.positions) << m->name;
        EXPECT_EQ(m->normals, ascii.normals) << m->name;
        EXPECT_EQ(m->indices, ascii.indices) << m->name;
    }
    ASSERT_EQ(ascii.normals.size(), 8u);
    for (size_t v = 0; v < 8; ++v)
        expect_vec3_near(ascii.normals[v], glm::normalize(2.0f * ascii.positions[v] - 1.0f), 1e-6f);
    expect_unit_cube_surface(ascii);
}

TEST(io_load_obj, QuadsNormalsAndRelativeIndices)
{
    const auto mesh = jade::load_mesh(data("cube.obj"));
    ASSERT_EQ(mesh.positions.size(), 8u);
    EXPECT_EQ(mesh.triangle_count(), 12u);
    // Same vertex numbering and faces as cube_colors.off, so the same fan triangulation.
    EXPECT_EQ(mesh.indices, jade::load_mesh(data("cube_colors.off")).indices);
    ASSERT_EQ(mesh.normals.size(), 8u);
    EXPECT_EQ(mesh.normals[0], glm::vec3(-1, 0, 0));  // first face corner that names vertex 1
    EXPECT_EQ(mesh.normals[7], glm::vec3(1, 0, 0));
    expect_outward(mesh, glm::vec3(0.5f));
}

// ----------------------------------------------------------------------------------- glTF --

TEST(io_load_gltf, NodeTransformsAreApplied)
{
    const auto mesh = jade::load_mesh(data("nodes_transforms.gltf"));
    ASSERT_EQ(mesh.positions.size(), 12u);
    ASSERT_EQ(mesh.triangle_count(), 4u);
    ASSERT_EQ(mesh.normals.size(), 12u);
    const float s = std::sqrt(0.2f);  // (0.5, 1, 0) normalised is (s, 2s, 0)
    const std::vector<glm::vec3> positions = {
        {10, 0, 0}, {11, 0, 0}, {10, 1, 0},  // node 0: translation (10, 0, 0)
        {0, 5, 2},  {0, 7, 2},  {-2, 5, 2},  // node 2 under node 1: T(0,5,0) R(90° about z) S(2) · T(0,0,1)
        {0, 0, 0},  {-1, 0, 0}, {0, 1, 0},   // node 4: scale (-1, 1, 1), a mirror
        {2, 0, 0},  {0, 1, 0},  {2, 0, 1},   // node 5: scale (2, 1, 1) of the slope x + y = 1
    };
    const std::vector<glm::vec3> normals = {
        {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1},     {0, 0, 1},     {0, 0, 1},
        {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {s, 2 * s, 0}, {s, 2 * s, 0}, {s, 2 * s, 0},
    };
    for (size_t v = 0; v < 12; ++v) {
        expect_vec3_near(mesh.positions[v], positions[v], 1e-6f, "position " + std::to_string(v));
        expect_vec3_near(mesh.normals[v], normals[v], 1e-6f, "normal " + std::to_string(v));
    }
    // The mirrored instance has its winding reversed so that it still faces its normal.
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 8, 7, 9, 10, 11}));
    for (size_t t = 0; t < 4; ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), mesh.normals[mesh.indices[3 * t]]), 0.0f) << "triangle " << t;
    }
}

TEST(io_load_gltf, CubeSplitAtSeamsWeldsToEightVertices)
{
    const auto mesh = jade::load_mesh(data("cube_seams.gltf"));
    ASSERT_EQ(mesh.positions.size(), 24u);
    EXPECT_EQ(mesh.triangle_count(), 12u);
    EXPECT_EQ(mesh.normals.size(), 24u);
    EXPECT_TRUE(mesh.baked_ao.empty());
    const auto p = jade::prepare_mesh(mesh);
    EXPECT_EQ(p.vertex_count(), 8u);
    EXPECT_EQ(p.triangle_count(), 12u);
    EXPECT_EQ(p.welded_vertices, 16u);
    EXPECT_EQ(p.dropped_triangles, 0u);
    EXPECT_FLOAT_EQ(jade::dev::total_area(p), 24.0f);
    EXPECT_TRUE(closed_and_oriented(p));
    for (size_t v = 0; v < 24; ++v) EXPECT_EQ(p.positions[p.render_to_bake[v]], mesh.positions[v]);
    double area_sum = 0.0;
    for (size_t v = 0; v < 8; ++v) {
        // A corner touches one or two of the two triangles of each of its three faces: its
        // area is a multiple of 2/3, and its normal leans towards the faces it touches twice,
        // staying within 20° of the corner diagonal.
        const float thirds = p.areas[v] / (2.0f / 3.0f);
        EXPECT_FLOAT_EQ(thirds, std::round(thirds)) << "vertex " << v;
        EXPECT_GT(glm::dot(p.normals[v], p.positions[v] / std::sqrt(3.0f)), 0.94f) << "vertex " << v;
        area_sum += p.areas[v];
    }
    EXPECT_NEAR(area_sum, 24.0, 1e-5);
}

TEST(io_load_gltf, GlbGivesTheSameMeshAsGltf)
{
    const auto text = jade::load_mesh(data("cube_seams.gltf"));
    const auto binary = jade::load_mesh(data("cube_seams.glb"));
    EXPECT_EQ(binary.positions, text.positions);
    EXPECT_EQ(binary.normals, text.normals);
    EXPECT_EQ(binary.indices, text.indices);
}

TEST(io_load_gltf, TriangleStripAndFanAreConverted)
{
    const auto mesh = jade::load_mesh(data("strip_fan.gltf"));
    ASSERT_EQ(mesh.triangle_count(), 4u + 6u);
    EXPECT_TRUE(mesh.normals.empty());
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t << " is clockwise";
    }
    const auto p = jade::prepare_mesh(mesh);
    EXPECT_NEAR(jade::dev::total_area(p), 2.0f + 1.5f * std::sqrt(3.0f), 1e-5f);  // 1×2 strip + unit hexagon
}

TEST(io_load_gltf, SparseAccessorsAreExpanded)
{
    // make_test_data.py: positions 3 and 7 replaced, _AO without a bufferView (zeros) with four
    // sparse entries.
    const auto sparse = jade::load_mesh(data("sparse_cube.gltf"));
    const auto dense = jade::load_mesh(data("cube_seams.gltf"));
    ASSERT_EQ(sparse.positions.size(), dense.positions.size());
    for (size_t v = 0; v < dense.positions.size(); ++v) {
        const glm::vec3 expected = v == 3 ? glm::vec3(0, 0, 5) : v == 7 ? glm::vec3(0, 0, -5) : dense.positions[v];
        EXPECT_EQ(sparse.positions[v], expected) << "vertex " << v;
        EXPECT_EQ(sparse.normals[v], dense.normals[v]) << "vertex " << v;
        EXPECT_EQ(sparse.baked_ao[v], v < 4 ? 0.25f : 0.0f) << "vertex " << v;
    }
    EXPECT_EQ(sparse.indices, dense.indices);
}

// ------------------------------------------------------------------------- save_baked_gltf --

struct Baked {
    jade::TriangleMesh mesh;
    jade::BakedAttributes attributes;
};

Baked baked_sphere()
{
    Baked b;
    b.mesh = jade::procedural::sphere(1.5f, 12, 24);
    const size_t n = b.mesh.positions.size();
    for (size_t v = 0; v < n; ++v) {
        b.attributes.ao.push_back(float(v) / float(n));
        b.attributes.tm.push_back({0.1f * float(v), 1.0f / float(v + 1), -float(v)});
    }
    b.attributes.extras_json = R"({"jade": {"rays": 64, "seed": 1234567890123, "note": null, "name": "sphère"}})";
    return b;
}

void expect_round_trip(const std::filesystem::path& path)
{
    const auto b = baked_sphere();
    jade::save_baked_gltf(path, b.mesh, b.attributes);
    const auto loaded = jade::load_mesh(path);
    EXPECT_EQ(loaded.positions, b.mesh.positions);
    EXPECT_EQ(loaded.normals, b.mesh.normals);
    EXPECT_EQ(loaded.indices, b.mesh.indices);
    EXPECT_EQ(loaded.baked_ao, b.attributes.ao);
    EXPECT_EQ(loaded.baked_tm, b.attributes.tm);
}

TEST(io_save_gltf, GlbRoundTripsPositionsIndicesAndAttributes)
{
    const auto path = out("save/sphere.glb");
    expect_round_trip(path);
    // The container: 4-byte aligned JSON and BIN chunks that add up to the declared length.
    const auto bytes = read_bytes(path);
    ASSERT_GE(bytes.size(), 28u);
    uint32_t header[5];
    std::memcpy(header, bytes.data(), sizeof header);
    EXPECT_EQ(std::string(bytes.data(), 4), "glTF");
    EXPECT_EQ(header[1], 2u);
    EXPECT_EQ(header[2], bytes.size());
    EXPECT_EQ(header[3] % 4, 0u);
    uint32_t bin_length;
    std::memcpy(&bin_length, bytes.data() + 20 + header[3], 4);
    EXPECT_EQ(20 + header[3] + 8 + bin_length, bytes.size());
    EXPECT_EQ(bin_length % 4, 0u);
}

TEST(io_save_gltf, GltfRoundTripsAndStoresExtrasAndBounds)
{
    const auto path = out("save/sphere.gltf");
    expect_round_trip(path);
    const auto doc = nlohmann::json::parse(read_bytes(path));
    const auto expected = nlohmann::json::parse(baked_sphere().attributes.extras_json);
    EXPECT_EQ(doc["asset"]["version"], "2.0");
    EXPECT_EQ(doc["asset"]["extras"], expected);  // null, a 41-bit integer and UTF-8 kept exactly
    const auto& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
    for (const char* name : {"POSITION", "NORMAL", "_AO", "_TM"}) EXPECT_TRUE(attributes.contains(name)) << name;
    const auto& ao = doc["accessors"][attributes["_AO"].get<int>()];
    EXPECT_EQ(ao["type"], "SCALAR");
    EXPECT_EQ(ao["componentType"], 5126);
    const auto& position = doc["accessors"][attributes["POSITION"].get<int>()];
    EXPECT_EQ(position["min"], nlohmann::json({-1.5, -1.5, -1.5}));
    EXPECT_EQ(position["max"], nlohmann::json({1.5, 1.5, 1.5}));
    EXPECT_EQ(doc["buffers"][0]["uri"].get<std::string>().rfind("data:application/octet-stream;base64,", 0), 0u);
}

TEST(io_save_gltf, WithoutAttributesWritesPlainGeometry)
{
    const auto path = out("save/plain.glb");
    jade::save_baked_gltf(path, jade::dev::procedural::grid(2, 1.0f), {});
    const auto loaded = jade::load_mesh(path);
    EXPECT_EQ(loaded.triangle_count(), 8u);
    EXPECT_TRUE(loaded.baked_ao.empty());
    EXPECT_TRUE(loaded.baked_tm.empty());
}

TEST(io_save_gltf, FailuresLeaveNoFileBehind)
{
    const auto path = out("save/atomic.glb");
    auto b = baked_sphere();
    jade::save_baked_gltf(path, b.mesh, b.attributes);
    const auto before = read_bytes(path);

    b.attributes.extras_json = "{not json";
    EXPECT_NE(error_of([&] {
                  jade::save_baked_gltf(path, b.mesh, b.attributes);
              }).find("atomic.glb: extras_json is not valid JSON"),
              std::string::npos);
    b.attributes.extras_json = "[1, 2]";
    EXPECT_EQ(error_of([&] { jade::save_baked_gltf(path, b.mesh, b.attributes); }),
              "atomic.glb: extras_json must be a JSON object");
    b.attributes.extras_json.clear();
    b.attributes.ao.pop_back();
    EXPECT_NE(error_of([&] { jade::save_baked_gltf(path, b.mesh, b.attributes); }).find("_AO values for"),
              std::string::npos);
    EXPECT_EQ(read_bytes(path), before);  // the earlier file is untouched

    const auto missing_dir = path.parent_path() / "no such folder" / "x.glb";
    EXPECT_NE(error_of([&] { jade::save_baked_gltf(missing_dir, b.mesh, {}); }).find("x.glb: "), std::string::npos);
    EXPECT_NE(error_of([&] { jade::save_baked_gltf(path.parent_path() / "x.stl", b.mesh, {}); }).find(".glb, .gltf"),
              std::string::npos);
    for (const auto& entry : std::filesystem::directory_iterator(path.parent_path()))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

// ------------------------------------------------------------------------------ save_image --

/// Reads an image back as floats through OpenImageIO, alpha kept straight.
std::vector<float> read_image(const std::filesystem::path& path, OIIO::ImageSpec& spec)
{
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path.string(), &config);
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return {};
    spec = in->spec();
    std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    return pixels;
}

std::vector<float> gradient(int width, int height)
{
    std::vector<float> rgba;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            rgba.insert(rgba.end(), {float(x) / float(width - 1), float(y) / float(height - 1), 0.25f,
                                     1.0f - 0.5f * float(x) / float(width - 1)});
    return rgba;
}

TEST(io_save_image, PngIsSrgbEncodedEightBitWithAlpha)
{
    const auto path = out("image/gradient.png");
    const int w = 9, h = 3;
    auto rgba = gradient(w, h);
    rgba[0] = -1.0f;                                    // clamped to 0
    rgba[1] = 7.0f;                                     // clamped to 1
    rgba[2] = std::numeric_limits<float>::quiet_NaN();  // NaN becomes 0
    jade::save_image(path, w, h, rgba);
    OIIO::ImageSpec spec;
    const auto back = read_image(path, spec);
    ASSERT_EQ(spec.width, w);
    ASSERT_EQ(spec.height, h);
    ASSERT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT8);
    auto srgb = [](float v) {
        v = std::clamp(v, 0.0f, 1.0f);
        return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    };
    for (size_t i = 0; i < back.size(); ++i) {
        const float source = std::isnan(rgba[i]) ? 0.0f : rgba[i];
        const float expected =
            std::round((i % 4 == 3 ? std::clamp(source, 0.0f, 1.0f) : srgb(source)) * 255.0f) / 255.0f;
        ASSERT_NEAR(back[i], expected, 1e-6f) << "value " << i;
    }
    EXPECT_NEAR(back[4 * 4], 188.0f / 255.0f, 1e-6f);  // linear 0.5 (x = 4 of 8) is sRGB 188
}

TEST(io_save_image, ExrIsLinearHalfFloat)
{
    const auto path = out("image/gradient.exr");
    const int w = 5, h = 4;
    auto rgba = gradient(w, h);
    rgba[0] = 3.5f;  // HDR values survive
    jade::save_image(path, w, h, rgba);
    OIIO::ImageSpec spec;
    const auto back = read_image(path, spec);
    ASSERT_EQ(back.size(), rgba.size());
    EXPECT_EQ(spec.format, OIIO::TypeDesc::HALF);
    for (size_t i = 0; i < back.size(); ++i)
        EXPECT_NEAR(back[i], rgba[i], 1e-3f * std::max(1.0f, rgba[i])) << "value " << i;
    EXPECT_EQ(back[0], 3.5f);
}

TEST(io_save_image, RejectsUnknownFormatsAndWrongSizes)
{
    const auto path = out("image/picture.bmp");
    const auto message = error_of([&] { jade::save_image(path, 2, 2, std::vector<float>(16, 0.5f)); });
    EXPECT_NE(message.find("picture.bmp"), std::string::npos) << message;
    EXPECT_NE(message.find(".png"), std::string::npos) << message;
    EXPECT_NE(message.find(".exr"), std::string::npos) << message;
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_THROW(jade::save_image(out("image/short.png"), 2, 2, std::vector<float>(15, 0.5f)), jade::Error);
    EXPECT_THROW(jade::save_image(out("image/empty.png"), 0, 2, {}), jade::Error);
}

}  // namespace
