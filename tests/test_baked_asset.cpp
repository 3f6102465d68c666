// A baked file carries everything the default shading needs (docs/gltf.md): `jade render` of
// it draws what `jade render` of its source draws; the JADE_materials_translucency extension
// reads back bit for bit and refuses bad values naming file, material and property; the
// thickness map of a UV-mapped asset holds the per-vertex thickness interpolated over the UV
// layout; the Khronos glTF Validator accepts both outputs.
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include "flip.hpp"
#include "gltf_reader.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

namespace {

using nlohmann::json;

std::filesystem::path folder()
{
    const auto dir = jade::test::test_folder("baked_asset");
    std::filesystem::create_directories(dir);
    return dir;
}

jade::flip::Image load_png(const std::filesystem::path& path)
{
    const jade::dev::LoadedImage img = jade::dev::load_image(path);
    return jade::flip::from_linear(uint32_t(img.width), uint32_t(img.height), img.rgba.data(), 4);
}

void run_ok(const std::vector<std::string>& args)
{
    const auto r = jade::test::run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.output;
}

void expect_valid(const std::vector<std::filesystem::path>& files)
{
    std::string why;
    const auto reports = jade::test::run_gltf_validator(files, &why);
    if (!reports) GTEST_SKIP() << why;
    ASSERT_EQ(reports->size(), files.size()) << why;
    for (const auto& r : *reports) {
        std::string issues;
        for (const auto& i : r.issues) issues += "\n  " + i;
        EXPECT_EQ(r.errors, 0) << r.file << issues;
        EXPECT_EQ(r.warnings, 0) << r.file << issues;
    }
}

// The bunny baked with blue-jewel, rendered with no material flag, against the source rendered
// with the bake's settings (the same quality, so the same bake), front- and back-lit. Measured on
// lavapipe: LDR FLIP 0 here (128x128), 2.7e-7 and 7.3e-7 at 512x512 (a few pixels one 8-bit code
// apart: the renderer averages the per-render-vertex values of each welded vertex). Before the
// baked file carried its material and scattering normals, 512x512: 0.121 and 0.107 (a green
// bunny), 0.051 and 0.018 with --material blue-jewel given. The bound 1e-3 leaves room for a
// rasteriser that rounds differently and is far below what a wrong input costs: the baked file
// drawn with another material (checked below) is 0.1 away.
TEST(BakedAsset, RendersAsItsSource)
{
    const auto dir = folder();
    const std::string bunny = jade::test::asset("bunny00.off").string();
    const std::string baked = (dir / "bunny.glb").string();
    run_ok({"bake", bunny, "--material", "blue-jewel", "--quality", "draft", "--out", baked});
    for (const char* lights : {"default", "figure1"}) {
        SCOPED_TRACE(lights);
        const auto source = dir / (std::string("source_") + lights + ".png");
        const auto from_file = dir / (std::string("baked_") + lights + ".png");
        const auto other = dir / (std::string("baked_jade_") + lights + ".png");
        const std::vector<std::string> view = {"--size", "128x128", "--lights", lights};
        auto with = [&](std::vector<std::string> args) {
            args.insert(args.end(), view.begin(), view.end());
            return args;
        };
        run_ok(with({"render", bunny, "--material", "blue-jewel", "--quality", "draft", "--out", source.string()}));
        run_ok(with({"render", baked, "--out", from_file.string()}));
        run_ok(with({"render", baked, "--material", "jade", "--out", other.string()}));
        const double same = jade::flip::ldr_flip(load_png(source), load_png(from_file));
        const double different = jade::flip::ldr_flip(load_png(source), load_png(other));
        std::printf("%s lights: FLIP baked file vs source %.5f; with --material jade %.5f\n", lights, same, different);
        EXPECT_LE(same, 1e-3);
        EXPECT_GE(different, 0.05);  // the explicit flag still overrides the file's material
    }

    // A glTF source whose primitive has no material: the bake's material goes to one made for it.
    const std::string cube = jade::test::data("cube_seams.gltf").string();
    const std::string cube_baked = (dir / "cube.glb").string();
    run_ok({"bake", cube, "--material", "blue-jewel", "--quality", "draft", "--out", cube_baked});
    const std::vector<std::string> view = {"--size", "96x96", "--eye", "3,2,4"};
    std::vector<std::string> source = {"render",    cube,    "--material", "blue-jewel",
                                       "--quality", "draft", "--out",      (dir / "cube_source.png").string()};
    std::vector<std::string> from_file = {"render", cube_baked, "--out", (dir / "cube_baked.png").string()};
    source.insert(source.end(), view.begin(), view.end());
    from_file.insert(from_file.end(), view.begin(), view.end());
    run_ok(source);
    run_ok(from_file);
    const double cube_flip = jade::flip::ldr_flip(load_png(dir / "cube_source.png"), load_png(dir / "cube_baked.png"));
    std::printf("cube_seams.gltf: FLIP baked file vs source %.5f\n", cube_flip);
    EXPECT_LE(cube_flip, 1e-3);
    expect_valid({baked, cube_baked});
}

/// A material with one profile of each kind and every renderer parameter set apart from its default.
jade::Material every_kind_of_material()
{
    jade::Material m = jade::material_preset("skin1", 1.0);  // dipole profiles, transmission on
    m.name = "every kind";
    m.profile[1] = jade::material_preset("skin", 1.0).profile[1];  // Gaussians
    m.profile[2] = jade::ChannelProfile::burley(0.3);
    m.albedo = glm::vec3(0.7f, 0.31f, 0.123456789f);
    m.strength = 0.37f, m.spread_strength = 4.5f, m.ior = 1.44f, m.roughness = 0.3f, m.specular = 0.8f;
    m.boundary_transmittance = true;
    m.transmission.sigma_t = glm::vec3(3.5f, 4.25f, 1e-3f);
    m.transmission.sigma_s_reduced = glm::vec3(2.0f, 2.5f, 3.0f);
    m.transmission.sigma_tr = glm::vec3(0.1f, 0.2f, 0.3f);
    m.transmission.source_depth = glm::vec3(0.33f);
    m.transmission.extrapolation = glm::vec3(0.25f);
    m.transmission.weight = 0.4f, m.transmission.diffusion_weight = 0.2f;
    m.transmission.lobe = 16.0f, m.transmission.normal_mix = 0.25f;
    return m;
}

TEST(BakedAsset, TranslucencyExtensionRoundTripsAndRefusesBadValues)
{
    const auto dir = folder();
    const jade::TriangleMesh mesh = jade::procedural::sphere(1.0f, 6, 8);
    const size_t n = mesh.positions.size();
    jade::BakedAttributes baked;
    for (size_t i = 0; i < n; ++i) {
        baked.ao.push_back(float(i % 7) / 7.0f);
        baked.tm.push_back(glm::vec3(0.5f, 0.25f, float(i) / float(n)));
        baked.thickness.push_back(0.01f * float(i + 1));
        baked.scattering_normal.push_back(glm::normalize(mesh.positions[i] + glm::vec3(0.0f, 0.1f, 0.0f)));
        baked.normal_spread.push_back(glm::vec3(0.0f, 0.5f, float(i) / float(n)));
    }
    const jade::Material m = every_kind_of_material();
    baked.material = m;
    const auto path = dir / "sphere.gltf";
    jade::save_baked_gltf(path, mesh, baked);

    // Jade's reader: every parameter bit for bit.
    std::optional<jade::Material> read;
    jade::ReadOptions options;
    options.baked_material = &read;
    const jade::TriangleMesh back = jade::load_mesh(path, options);
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->name, m.name);
    EXPECT_EQ(read->albedo, m.albedo);
    EXPECT_EQ(read->strength, m.strength);
    EXPECT_EQ(read->spread_strength, m.spread_strength);
    EXPECT_EQ(read->ior, m.ior);
    EXPECT_EQ(read->roughness, m.roughness);
    EXPECT_EQ(read->specular, m.specular);
    EXPECT_EQ(read->boundary_transmittance, m.boundary_transmittance);
    EXPECT_EQ(read->profile, m.profile);
    const jade::Transmission &a = read->transmission, &b = m.transmission;
    EXPECT_TRUE(a.sigma_t == b.sigma_t && a.sigma_s_reduced == b.sigma_s_reduced && a.sigma_tr == b.sigma_tr &&
                a.source_depth == b.source_depth && a.extrapolation == b.extrapolation && a.weight == b.weight &&
                a.diffusion_weight == b.diffusion_weight && a.lobe == b.lobe && a.normal_mix == b.normal_mix);
    EXPECT_EQ(back.baked_scattering_normal, baked.scattering_normal);
    EXPECT_EQ(back.baked_normal_spread, baked.normal_spread);

    // An independent reader sees the documented form: a vendor extension, used and not required.
    const jade::test::GltfFile file = jade::test::read_gltf_file(path);
    const json& ext = file.doc["materials"][0]["extensions"]["JADE_materials_translucency"];
    EXPECT_EQ(ext["albedo"][2].get<double>(), double(m.albedo.z));
    EXPECT_EQ(ext["transmission"]["sigmaT"][1].get<double>(), double(m.transmission.sigma_t.y));
    EXPECT_EQ(ext["profiles"][0]["kind"], "dipole");
    EXPECT_EQ(ext["profiles"][1]["kind"], "gaussians");
    EXPECT_EQ(ext["profiles"][2]["d"].get<double>(), 0.3);
    EXPECT_EQ(file.doc["extensionsUsed"], json::array({"JADE_materials_translucency"}));
    EXPECT_FALSE(file.doc.contains("extensionsRequired"));
    const json& attributes = file.doc["meshes"][0]["primitives"][0]["attributes"];
    for (const char* name : {"_SCATTERING_NORMAL", "_NORMAL_SPREAD"}) {
        const json& accessor = file.doc["accessors"][attributes[name].get<size_t>()];
        EXPECT_EQ(accessor["type"], "VEC3") << name;
        EXPECT_EQ(accessor["componentType"], 5126) << name;
    }
    expect_valid({path});

    // Hostile values: refused, naming the file, the material and the property.
    std::ifstream in(path);
    const json original = json::parse(in);
    const std::vector<std::tuple<std::string, json, std::string>> bad = {
        {"/albedo/1", -0.5, "albedo[1]"},
        {"/ior", 9.0, "ior"},
        {"/strength", "high", "strength is not a number"},
        {"/transmission/normalMix", 2.0, "transmission.normalMix"},
        {"/transmission/sigmaT", json::array({1.0, 2.0}), "transmission.sigmaT is not an array of 3"},
        {"/profiles/2/d", 0.0, "profiles[2].d"},
        {"/profiles/0/kind", "cubic", "profiles[0].kind"},
        {"/profiles/1/weights/0", 0.9, "profiles[1].weights sum to"},
        {"/boundaryTransmittance", 1, "boundaryTransmittance is not true or false"},
        {"/transmission/sigmaTr/0", 1e39, "transmission.sigmaTr[0]"},
    };
    for (const auto& [pointer, value, what] : bad) {
        json doc = original;
        doc["materials"][0]["extensions"]["JADE_materials_translucency"][json::json_pointer(pointer)] = value;
        const auto bad_path = dir / "bad.gltf";
        std::ofstream(bad_path) << doc.dump();
        std::optional<jade::Material> none;
        jade::ReadOptions o;
        o.baked_material = &none;
        const std::string error = jade::test::error_of([&] { jade::load_mesh(bad_path, o); });
        EXPECT_NE(error.find("bad.gltf"), std::string::npos) << pointer << ": " << error;
        EXPECT_NE(error.find("material 0: JADE_materials_translucency." + what), std::string::npos)
            << pointer << ": " << error;
    }
    // Missing is as bad as wrong.
    json doc = original;
    doc["materials"][0]["extensions"]["JADE_materials_translucency"].erase("albedo");
    std::ofstream(dir / "missing.gltf") << doc.dump();
    std::optional<jade::Material> none;
    jade::ReadOptions o;
    o.baked_material = &none;
    EXPECT_NE(jade::test::error_of([&] {
                  jade::load_mesh(dir / "missing.gltf", o);
              }).find("JADE_materials_translucency.albedo is missing"),
              std::string::npos);
}

/// Signed twice the area of (a, b, c).
double cross2(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c)
{
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// tests/data/uv_slab.gltf: a slab whose faces lie in their own tiles of a UV atlas, at node
// scale 2, with a material Jade maps translucent. Every texel whose centre lies inside a UV
// triangle must hold the thickness interpolated there (barycentric, in mesh units: the baked
// world-space value / 2), as a fraction of thicknessFactor in 8 bits (within half a code); texels
// next to a triangle are grown (dilated), texels far from every triangle stay 0.
TEST(BakedAsset, ThicknessMapHoldsTheInterpolatedThickness)
{
    const auto dir = folder();
    const auto out = dir / "uv_slab.glb";
    run_ok({"bake", jade::test::data("uv_slab.gltf").string(), "--quality", "draft", "--out", out.string()});
    const jade::test::GltfFile file = jade::test::read_gltf_file(out);
    const json& material = file.doc["materials"][0];
    ASSERT_TRUE(material["extensions"].contains("KHR_materials_diffuse_transmission"));
    const json& volume = material["extensions"]["KHR_materials_volume"];
    ASSERT_TRUE(volume.contains("thicknessTexture")) << volume.dump();
    const double factor = volume["thicknessFactor"].get<double>();
    const double scale = file.doc["nodes"][0]["scale"][0].get<double>();
    const int texture = volume["thicknessTexture"]["index"].get<int>();
    const int image = file.doc["textures"][size_t(texture)]["source"].get<int>();
    const auto png = dir / "thickness.png";
    {
        const auto bytes = file.image(image);
        std::ofstream(png, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    // load_image decodes every 8-bit PNG as sRGB; the map is data: encode back to the stored codes
    // (exact for all 256 codes, checked first).
    auto code = [](float linear) {
        const float v = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
        return int(std::lround(v * 255.0f));
    };
    for (int c = 0; c < 256; ++c) {
        const float v = float(c) / 255.0f;
        ASSERT_EQ(code(v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f)), c);
    }
    const jade::dev::LoadedImage img = jade::dev::load_image(png);
    ASSERT_EQ(img.width, img.height);
    const int size = img.width;
    EXPECT_TRUE(size >= 16 && size <= 1024 && (size & (size - 1)) == 0) << size;
    std::vector<int> g(size_t(size) * size);
    for (size_t i = 0; i < g.size(); ++i) {
        g[i] = code(img.rgba[4 * i + 1]);
        ASSERT_EQ(code(img.rgba[4 * i]), 0) << "R of texel " << i;  // thickness in G alone
        ASSERT_EQ(code(img.rgba[4 * i + 2]), 0) << "B of texel " << i;
    }

    const json& prim = file.doc["meshes"][0]["primitives"][0];
    const std::vector<float> uv = file.floats(prim["attributes"]["TEXCOORD_0"].get<int>());
    const std::vector<float> thickness = file.floats(prim["attributes"]["_THICKNESS"].get<int>());
    std::vector<uint32_t> indices;
    for (const auto& e : file.elements(prim["indices"].get<int>())) {
        uint16_t v;
        std::memcpy(&v, e.data(), sizeof v);
        indices.push_back(v);
    }
    // The size rule (docs/gltf.md): the smallest power of two N >= 4 sqrt(A3 / Auv) / median edge,
    // in [16, 1024]; the ratio does not depend on the node's scale.
    {
        const std::vector<float> pos = file.floats(prim["attributes"]["POSITION"].get<int>());
        double area3 = 0.0, area_uv = 0.0;
        std::vector<double> edges;
        for (size_t k = 0; k + 2 < indices.size(); k += 3) {
            glm::dvec3 p[3];
            glm::dvec2 q[3];
            for (int c = 0; c < 3; ++c) {
                const uint32_t v = indices[k + size_t(c)];
                p[c] = glm::dvec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
                q[c] = glm::dvec2(uv[2 * v], uv[2 * v + 1]);
                edges.push_back(glm::length(p[c] - p[(c + 2) % 3]));
            }
            area3 += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
            area_uv += 0.5 * std::abs(cross2(q[0], q[1], q[2]));
        }
        std::sort(edges.begin(), edges.end());
        const double texels = 4.0 * std::sqrt(area3 / area_uv) / edges[edges.size() / 2];
        int expected = 16;
        while (expected < 1024 && expected < texels) expected *= 2;
        EXPECT_EQ(size, expected) << texels << " texels per UV unit wanted";
    }
    float largest = 0.0f;
    for (float t : thickness) largest = std::max(largest, t);
    EXPECT_NEAR(factor, double(largest) / scale, 1e-9 * factor);  // the largest thickness, mesh units

    std::vector<uint8_t> inside(g.size(), 0);
    size_t checked = 0;
    double worst = 0.0;
    for (size_t k = 0; k + 2 < indices.size(); k += 3) {
        glm::dvec2 p[3];
        double t[3];
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = indices[k + size_t(c)];
            p[c] = glm::dvec2(uv[2 * v], uv[2 * v + 1]) * double(size);
            t[c] = double(thickness[v]) / scale;
        }
        const double area = cross2(p[0], p[1], p[2]);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::dvec2 q(x + 0.5, y + 0.5);
                const double w0 = cross2(q, p[1], p[2]) / area, w1 = cross2(p[0], q, p[2]) / area;
                const double w2 = 1.0 - w0 - w1;
                if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
                inside[size_t(y) * size + size_t(x)] = 1;
                // Centres on an edge may take either triangle's value: check strict insides only.
                if (w0 < 1e-6 || w1 < 1e-6 || w2 < 1e-6) continue;
                const double expected = (w0 * t[0] + w1 * t[1] + w2 * t[2]) / factor * 255.0;
                const double error = std::abs(double(g[size_t(y) * size + size_t(x)]) - expected);
                worst = std::max(worst, error);
                ++checked;
                EXPECT_LE(error, 0.5 + 1e-6)
                    << "texel " << x << "," << y << ": " << g[size_t(y) * size + size_t(x)] << " for " << expected;
            }
    }
    std::printf("%dx%d map, thicknessFactor %.5g mesh units; %zu texels inside triangles, worst error %.3f codes\n",
                size, size, factor, checked, worst);
    EXPECT_GE(checked, size_t(size) * size / 4);
    // Dilation: a texel outside every triangle next to one inside is grown; one more than 4
    // texels (the dilation) from every inside texel is 0.
    size_t grown = 0, empty = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (inside[size_t(y) * size + size_t(x)]) continue;
            int nearest = 1 << 20;
            for (int dy = -5; dy <= 5; ++dy)
                for (int dx = -5; dx <= 5; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < size && yy < size && inside[size_t(yy) * size + size_t(xx)])
                        nearest = std::min(nearest, std::max(std::abs(dx), std::abs(dy)));
                }
            if (nearest == 1) {
                EXPECT_GT(g[size_t(y) * size + size_t(x)], 0) << "texel " << x << "," << y;
                ++grown;
            }
            if (nearest > 4) {
                EXPECT_EQ(g[size_t(y) * size + size_t(x)], 0) << "texel " << x << "," << y;
                ++empty;
            }
        }
    EXPECT_GT(grown, 0u);
    EXPECT_GT(empty, 0u);

    // Baked again in place: the map replaces its predecessor (same image, texture, sampler) and
    // the binary data do not grow.
    const auto again = dir / "uv_slab_again.glb";
    std::filesystem::copy_file(out, again);
    run_ok({"bake", again.string(), "--in-place", "--quality", "draft"});
    const jade::test::GltfFile twice = jade::test::read_gltf_file(again);
    for (const char* key : {"images", "textures", "samplers", "bufferViews", "accessors"})
        EXPECT_EQ(twice.doc[key].size(), file.doc[key].size()) << key;
    ASSERT_EQ(twice.buffers.size(), 1u);
    EXPECT_EQ(twice.buffers[0].size(), file.buffers[0].size());  // the JSON's record holds timings
    expect_valid({out, again});
}

}  // namespace
