// `jade bake` on glTF assets keeps the whole asset: every sample of tests/data/gltf_samples
// (assimp-testmodels) and every glTF file of tests/data is baked once, read back with an
// independent reader (support/gltf_reader.cpp) and compared with its input element by element;
// the Khronos glTF Validator checks each output; the loaders, `jade render`, `jade info` and
// `jade deform --deformer gltf` read the baked files.
#include <jade/io.hpp>
#include <jade/scene.hpp>

#include "gltf_reader.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using jade::test::GltfFile;
using nlohmann::json;

/// Attributes the bake owns: an input's earlier ones are replaced.
const std::set<std::string> kBaked = {"_AO", "_TM", "_THICKNESS", "_SCATTERING_NORMAL", "_NORMAL_SPREAD"};

struct Baked {
    std::filesystem::path input, output;
    jade::test::CliResult cli;
};

/// Every input: the sample assets and every glTF file of tests/data.
std::vector<std::filesystem::path> inputs()
{
    std::vector<std::filesystem::path> out;
    for (const char* s : {"2CylinderEngine.glb", "BoxTextured.glb", "BoxTextured_external/BoxTextured.gltf",
                          "simple_skin.gltf", "AnimatedMorphCube.gltf"})
        out.push_back(jade::test::data("gltf_samples") / s);
    for (const auto& entry : std::filesystem::directory_iterator(jade::test::data("")))
        if (entry.path().extension() == ".gltf" || entry.path().extension() == ".glb") out.push_back(entry.path());
    return out;
}

/// `input` baked (draft quality) to the other container format than its own, so that both
/// writers are covered; once per test process.
const Baked& baked(const std::filesystem::path& input)
{
    static std::map<std::filesystem::path, Baked> done;
    auto [it, added] = done.try_emplace(input);
    Baked& b = it->second;
    if (added) {
        b.input = input;
        // In the running test's own folder: ctest runs these tests as parallel processes, and
        // out() clears a path that another process may have baked and be reading.
        const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        b.output =
            jade::test::out("gltf_roundtrip/" + test + "/" + input.stem().string() + "_from_" +
                            input.extension().string().substr(1) + (input.extension() == ".glb" ? ".gltf" : ".glb"));
        b.cli = jade::test::run_cli({"bake", input.string(), "--out", b.output.string(), "--quality", "draft"});
    }
    return b;
}

const Baked& sample(const std::string& name) { return baked(jade::test::data("gltf_samples") / name); }
const Baked& own(const std::string& name) { return baked(jade::test::data(name)); }

const json& member(const json& j, const char* key)
{
    static const json none;
    return j.is_object() && j.contains(key) ? j[key] : none;
}

void expect_same_accessor(const GltfFile& in, const json& ia, const GltfFile& out, const json& ib,
                          const std::string& where)
{
    ASSERT_TRUE(ia.is_number_integer() && ib.is_number_integer()) << where;
    const json& a = in.doc["accessors"][ia.get<size_t>()];
    const json& b = out.doc["accessors"][ib.get<size_t>()];
    for (const char* key :
         {"componentType", "type", "count", "normalized", "name", "min", "max", "extras", "extensions"})
        if (a.contains(key)) EXPECT_EQ(a[key], member(b, key)) << where << ": accessor property " << key;
    EXPECT_TRUE(in.elements(ia.get<int>()) == out.elements(ib.get<int>())) << where << ": accessor data differ";
}

/// Every property of `a` but the data-bearing ones must be in `b` as equal JSON; the data are
/// compared through the accessors and images.
void expect_same_except(const json& a, const json& b, const std::set<std::string>& data_keys, const std::string& where)
{
    for (const auto& [key, value] : a.items())
        if (!data_keys.count(key)) EXPECT_EQ(value, member(b, key.c_str())) << where << "." << key;
}

void expect_asset_kept(const GltfFile& in, const GltfFile& out)
{
    const json& a = in.doc;
    const json& b = out.doc;
    // Scenes, nodes (names, TRS, matrices, hierarchy), cameras, textures, samplers, top-level
    // extensions and extras, and any property Jade does not know: identical JSON.
    expect_same_except(a, b,
                       {"asset", "buffers", "bufferViews", "accessors", "images", "meshes", "skins", "animations",
                        "materials", "extensionsUsed", "textures", "samplers"},
                       "document");
    // Textures and samplers as read; a thickness map adds one of each after them.
    for (const char* key : {"textures", "samplers"}) {
        ASSERT_GE(member(b, key).size(), member(a, key).size()) << key;
        for (size_t i = 0; i < member(a, key).size(); ++i) EXPECT_EQ(a[key][i], b[key][i]) << key << " " << i;
    }
    EXPECT_EQ(a["asset"]["version"], b["asset"]["version"]);
    expect_same_except(a["asset"], b["asset"], {"extras"}, "asset");
    for (const auto& [key, value] : member(a["asset"], "extras").items())
        if (key != "jade") EXPECT_EQ(value, b["asset"]["extras"][key]) << "asset.extras." << key;
    for (const auto& ext : member(a, "extensionsUsed"))
        EXPECT_NE(std::find(b["extensionsUsed"].begin(), b["extensionsUsed"].end(), ext), b["extensionsUsed"].end())
            << ext;

    ASSERT_EQ(member(a, "meshes").size(), member(b, "meshes").size());
    for (size_t m = 0; m < member(a, "meshes").size(); ++m) {
        const json& ma = a["meshes"][m];
        const json& mb = b["meshes"][m];
        expect_same_except(ma, mb, {"primitives"}, "mesh " + std::to_string(m));
        ASSERT_EQ(ma["primitives"].size(), mb["primitives"].size());
        for (size_t p = 0; p < ma["primitives"].size(); ++p) {
            const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            const json& pa = ma["primitives"][p];
            const json& pb = mb["primitives"][p];
            expect_same_except(pa, pb, {"attributes", "indices", "targets", "material"}, where);
            // A primitive without a material may get the one made for the bake's material.
            if (pa.contains("material"))
                EXPECT_EQ(pa["material"], member(pb, "material")) << where;
            else if (pb.contains("material"))
                EXPECT_EQ(b["materials"][pb["material"].get<size_t>()]["name"], "jade bake") << where;
            for (const auto& [name, index] : pa["attributes"].items())
                if (!kBaked.count(name))
                    expect_same_accessor(in, index, out, member(pb["attributes"], name.c_str()), where + " " + name);
            if (pa.contains("indices"))
                expect_same_accessor(in, pa["indices"], out, member(pb, "indices"), where + " indices");
            ASSERT_EQ(member(pa, "targets").size(), member(pb, "targets").size()) << where;
            for (size_t t = 0; t < member(pa, "targets").size(); ++t)
                for (const auto& [name, index] : pa["targets"][t].items())
                    expect_same_accessor(in, index, out, member(pb["targets"][t], name.c_str()),
                                         where + " target " + std::to_string(t) + " " + name);
        }
    }
    ASSERT_EQ(member(a, "skins").size(), member(b, "skins").size());
    for (size_t s = 0; s < member(a, "skins").size(); ++s) {
        expect_same_except(a["skins"][s], b["skins"][s], {"inverseBindMatrices"}, "skin " + std::to_string(s));
        if (a["skins"][s].contains("inverseBindMatrices"))
            expect_same_accessor(in, a["skins"][s]["inverseBindMatrices"], out, b["skins"][s]["inverseBindMatrices"],
                                 "skin");
    }
    ASSERT_EQ(member(a, "animations").size(), member(b, "animations").size());
    for (size_t k = 0; k < member(a, "animations").size(); ++k) {
        const json& aa = a["animations"][k];
        const json& ab = b["animations"][k];
        expect_same_except(aa, ab, {"samplers"}, "animation " + std::to_string(k));
        ASSERT_EQ(aa["samplers"].size(), ab["samplers"].size());
        for (size_t s = 0; s < aa["samplers"].size(); ++s) {
            const std::string where = "animation " + std::to_string(k) + " sampler " + std::to_string(s);
            expect_same_except(aa["samplers"][s], ab["samplers"][s], {"input", "output"}, where);
            expect_same_accessor(in, aa["samplers"][s]["input"], out, ab["samplers"][s]["input"], where + " input");
            expect_same_accessor(in, aa["samplers"][s]["output"], out, ab["samplers"][s]["output"], where + " output");
        }
    }
    // The input's images, then the thickness maps Jade added (docs/gltf.md).
    ASSERT_GE(member(b, "images").size(), member(a, "images").size());
    for (size_t i = member(a, "images").size(); i < member(b, "images").size(); ++i)
        EXPECT_EQ(b["images"][i]["name"].get<std::string>().rfind("jade thickness map", 0), 0u) << "image " << i;
    for (size_t i = 0; i < member(a, "images").size(); ++i) {
        expect_same_except(a["images"][i], b["images"][i], {"uri", "bufferView"}, "image " + std::to_string(i));
        EXPECT_TRUE(in.image(int(i)) == out.image(int(i))) << "image " << i << ": bytes differ";
        EXPECT_FALSE(b["images"][i].contains("uri") && b["images"][i]["uri"].get<std::string>().rfind("data:", 0) != 0)
            << "image " << i << " still refers to an external file";
    }
    // The input's materials, then at most one for baked primitives that had none.
    ASSERT_GE(member(b, "materials").size(), member(a, "materials").size());
    ASSERT_LE(member(b, "materials").size(), member(a, "materials").size() + 1);
    if (member(b, "materials").size() > member(a, "materials").size()) {
        const json& made = b["materials"][member(a, "materials").size()];
        EXPECT_EQ(made["name"], "jade bake");
        EXPECT_EQ(made.size(), 2u) << made.dump();  // the name and the extension alone
        EXPECT_TRUE(made["extensions"].contains("JADE_materials_translucency")) << made.dump();
    }
    for (size_t m = 0; m < member(a, "materials").size(); ++m) {
        json ma = a["materials"][m], mb = b["materials"][m];
        // The extensions a preset-only translucent material gets (jade/io.hpp save_baked_asset).
        const bool preset = member(member(ma, "extras"), "jade").contains("preset");
        if (preset && !member(ma, "extensions").contains("KHR_materials_diffuse_transmission")) {
            EXPECT_TRUE(mb["extensions"].contains("KHR_materials_diffuse_transmission")) << "material " << m;
            for (const char* ext : {"KHR_materials_diffuse_transmission", "KHR_materials_volume"})
                if (!member(ma, "extensions").contains(ext)) mb["extensions"].erase(ext);
        }
        // What every baked material gets: Jade's own record of the material, and, with a
        // thickness map, the map in KHR_materials_volume (checked in test_baked_asset).
        if (mb.contains("extensions")) {
            json& ext = mb["extensions"];
            if (ext.contains("JADE_materials_translucency")) {
                EXPECT_TRUE(ext["JADE_materials_translucency"].contains("albedo")) << "material " << m;
                ext.erase("JADE_materials_translucency");
            }
            if (ext.contains("KHR_materials_volume") && ext["KHR_materials_volume"].contains("thicknessTexture")) {
                const json& before = member(member(ma, "extensions"), "KHR_materials_volume");
                ext["KHR_materials_volume"].erase("thicknessTexture");
                if (before.contains("thicknessFactor"))
                    ext["KHR_materials_volume"]["thicknessFactor"] = before["thicknessFactor"];
            }
            if (!ma.contains("extensions") && ext.empty()) mb.erase("extensions");
        }
        EXPECT_EQ(ma, mb) << "material " << m;
    }
}

void expect_baked_attributes(const GltfFile& out)
{
    for (size_t m = 0; m < member(out.doc, "meshes").size(); ++m)
        for (size_t p = 0; p < out.doc["meshes"][m]["primitives"].size(); ++p) {
            const json& prim = out.doc["meshes"][m]["primitives"][p];
            const int mode = prim.value("mode", 4);
            if (mode < 4) continue;  // points and lines are not baked
            const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            const size_t n = out.doc["accessors"][prim["attributes"]["POSITION"].get<size_t>()]["count"].get<size_t>();
            for (const auto& [name, type] : std::map<std::string, std::string>{{"_AO", "SCALAR"},
                                                                               {"_TM", "VEC3"},
                                                                               {"_THICKNESS", "SCALAR"},
                                                                               {"_SCATTERING_NORMAL", "VEC3"},
                                                                               {"_NORMAL_SPREAD", "VEC3"}}) {
                if (name == "_THICKNESS" && !prim["attributes"].contains(name)) continue;
                ASSERT_TRUE(prim["attributes"].contains(name)) << where << " has no " << name;
                const int index = prim["attributes"][name].get<int>();
                const json& a = out.doc["accessors"][size_t(index)];
                EXPECT_EQ(a["count"].get<size_t>(), n) << where << " " << name;
                EXPECT_EQ(a["type"], type) << where << " " << name;
                EXPECT_EQ(a["componentType"], 5126) << where << " " << name;
                const std::vector<float> values = out.floats(index);
                for (float v : values) {
                    ASSERT_TRUE(std::isfinite(v)) << where << " " << name;
                    if (name == "_AO" || name == "_NORMAL_SPREAD")
                        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << where << " " << name << " " << v;
                    else if (name != "_SCATTERING_NORMAL")
                        ASSERT_GE(v, 0.0f) << where << " " << name;
                }
                if (name == "_SCATTERING_NORMAL")
                    for (size_t i = 0; i + 2 < values.size(); i += 3)
                        ASSERT_NEAR(std::hypot(values[i], values[i + 1], values[i + 2]), 1.0, 1e-5) << where;
            }
        }
}

TEST(GltfRoundTrip, EveryInputIsKeptWholeBakedOnEveryTrianglePrimitiveAndValid)
{
    std::vector<std::filesystem::path> outputs;
    ASSERT_GE(inputs().size(), 14u);
    for (const auto& input : inputs()) {
        const Baked& b = baked(input);
        SCOPED_TRACE(b.input.string() + " -> " + b.output.filename().string());
        ASSERT_EQ(b.cli.exit_code, 0) << b.cli.output;
        const GltfFile in = jade::test::read_gltf_file(b.input);
        const GltfFile out = jade::test::read_gltf_file(b.output);
        expect_asset_kept(in, out);
        expect_baked_attributes(out);
        EXPECT_EQ(out.doc["asset"]["extras"]["jade"]["version"], 2);
        EXPECT_EQ(member(out.doc, "buffers").size(), 1u);  // one self-contained buffer
        outputs.push_back(b.output);
    }
    // The Khronos glTF Validator on every file written: no error, no warning.
    std::string why;
    const auto reports = jade::test::run_gltf_validator(outputs, &why);
    if (!reports) GTEST_SKIP() << why;
    ASSERT_EQ(reports->size(), outputs.size()) << why;
    for (const auto& r : *reports) {
        std::string issues;
        for (const auto& i : r.issues) issues += "\n  " + i;
        EXPECT_EQ(r.errors, 0) << r.file << issues;
        EXPECT_EQ(r.warnings, 0) << r.file << issues;
    }
}

TEST(GltfRoundTrip, LoadersAndRenderReadTheBakedAttributes)
{
    const auto& engine = sample("2CylinderEngine.glb");
    const jade::TriangleMesh mesh = jade::load_mesh(engine.output);  // every instance of every mesh
    EXPECT_EQ(mesh.baked_ao.size(), mesh.positions.size());
    EXPECT_EQ(mesh.baked_tm.size(), mesh.positions.size());
    EXPECT_EQ(mesh.baked_thickness.size(), mesh.positions.size());
    const auto render = jade::test::run_cli(
        {"render", engine.output.string(), "--mode", "tm", "--size", "64x64", "--out",
         jade::test::out("gltf_roundtrip/LoadersAndRenderReadTheBakedAttributes/engine.png").string()});
    EXPECT_EQ(render.exit_code, 0) << render.output;
    EXPECT_NE(render.output.find("t_m read from"), std::string::npos) << render.output;  // not baked again

    const jade::AnimatedMesh skin = jade::load_animated_gltf(sample("simple_skin.gltf").output);
    EXPECT_TRUE(skin.skinned);
    EXPECT_EQ(skin.mesh.baked_tm.size(), skin.mesh.positions.size());
    const jade::AnimatedMesh morph = jade::load_animated_gltf(sample("AnimatedMorphCube.gltf").output);
    EXPECT_EQ(morph.morph_deltas.size(), 2u);
    EXPECT_EQ(morph.mesh.baked_ao.size(), morph.mesh.positions.size());

    // Adding the translucency extensions to a preset material leaves Jade's reading unchanged.
    std::vector<std::string> before, after;
    const jade::Scene a = jade::load_scene(jade::test::data("scene_mixed.gltf"), &before);
    const jade::Scene b = jade::load_scene(own("scene_mixed.gltf").output, &after);
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (size_t o = 0; o < a.objects.size(); ++o) {
        EXPECT_EQ(a.objects[o].material.opaque, b.objects[o].material.opaque) << a.objects[o].name;
        EXPECT_EQ(a.objects[o].material.profile, b.objects[o].material.profile) << a.objects[o].name;
        EXPECT_EQ(a.objects[o].material.strength, b.objects[o].material.strength) << a.objects[o].name;
    }
    EXPECT_EQ(before.size(), after.size());
}

TEST(GltfRoundTrip, DeformPlaysTheBakedSkinAndMorphTargets)
{
    for (const Baked* b :
         {&sample("simple_skin.gltf"), &sample("AnimatedMorphCube.gltf"), &own("skinned_morph_anim.gltf")}) {
        const std::string name = b->input.filename().string();
        const auto r = jade::test::run_cli(
            {"deform", b->output.string(), "--deformer", "gltf", "--frames", "3", "--size", "48x48", "--out",
             jade::test::out("gltf_roundtrip/deform_" + name + "/x").parent_path().string()});
        EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.output;
        EXPECT_NE(r.output.find("glTF animation"), std::string::npos) << r.output;
    }
}

TEST(GltfRoundTrip, InfoSaysWhatWasBakedAndHow)
{
    const auto r = jade::test::run_cli({"info", sample("2CylinderEngine.glb").output.string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* phrase :
         {"baked by jade     record version 2; AO 16 rays", "instance rule     each mesh baked once",
          "(first of 2 instances)", "material 0        jade", "bake              mesh 28 primitives 0,1:"})
        EXPECT_NE(r.output.find(phrase), std::string::npos) << phrase << "\n" << r.output;
    const auto skin = jade::test::run_cli({"info", sample("simple_skin.gltf").output.string()});
    EXPECT_NE(skin.output.find("its bind pose"), std::string::npos) << skin.output;
}

// ------------------------------------------------------------------------------ in place --

std::string read_all(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(GltfBakeInPlace, OutEqualToTheInputNeedsInPlace)
{
    const auto asset = jade::test::out("gltf_in_place/box.glb");
    std::filesystem::copy_file(jade::test::data("gltf_samples/BoxTextured.glb"), asset);
    const std::string original = read_all(asset);
    auto r = jade::test::run_cli({"bake", asset.string(), "--out", asset.string()});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("is the input file; give --in-place to replace it"), std::string::npos) << r.output;
    r = jade::test::run_cli(
        {"bake", asset.string(), "--in-place", "--out", (asset.parent_path() / "other.glb").string()});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    r = jade::test::run_cli({"bake", jade::test::data("cube.obj").string(), "--in-place"});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("is not a glTF file"), std::string::npos) << r.output;
    EXPECT_EQ(read_all(asset), original);

    // Twice in place: the second bake overwrites the first one's accessors instead of adding some.
    for (int pass = 0; pass < 2; ++pass) {
        r = jade::test::run_cli({"bake", asset.string(), "--in-place", "--quality", "draft"});
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    const GltfFile once =
        jade::test::read_gltf_file(jade::test::out("gltf_in_place/unused.glb").parent_path() / "box.glb");
    const GltfFile in = jade::test::read_gltf_file(jade::test::data("gltf_samples/BoxTextured.glb"));
    expect_asset_kept(in, once);
    expect_baked_attributes(once);
    // _AO, _TM, _THICKNESS, _SCATTERING_NORMAL, _NORMAL_SPREAD
    EXPECT_EQ(once.doc["accessors"].size(), in.doc["accessors"].size() + 5);
    EXPECT_EQ(once.doc["bufferViews"].size(), in.doc["bufferViews"].size() + 5);
    for (const auto& entry : std::filesystem::directory_iterator(asset.parent_path()))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

/// When to send SIGKILL: `delay` after the start, or (when `after_temp`) `delay` after the
/// bake's temporary file "<asset>.tmp-<pid>-<random>" has its first bytes, i.e. while it is written,
/// synced or renamed. A negative delay lets the bake finish.
struct Kill {
    std::chrono::microseconds delay;
    bool after_temp = false;
};

void bake_and_kill(const std::filesystem::path& asset, Kill when)
{
    const std::string cli = jade::test::cli().string(), file = asset.string();
    std::vector<std::string> words = {cli, "bake", file, "--in-place", "--quality", "draft", "--ao-rays", "4"};
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1), ::dup2(null, 2);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    if (when.after_temp) {
        // check_output_file's probe has the same prefix but stays empty.
        const std::string prefix = asset.filename().string() + ".tmp-" + std::to_string(pid) + "-";
        const auto temp_has_bytes = [&] {
            std::error_code ec;
            for (const auto& e : std::filesystem::directory_iterator(asset.parent_path(), ec))
                if (e.path().filename().string().rfind(prefix, 0) == 0 && e.file_size(ec) > 0 && !ec) return true;
            return false;
        };
        int status = 0;
        while (!temp_has_bytes() && ::waitpid(pid, &status, WNOHANG) == 0)
            std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    if (when.delay.count() >= 0) {
        std::this_thread::sleep_for(when.delay);
        ::kill(pid, SIGKILL);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
}

TEST(GltfBakeInPlace, SigkillAtAnyMomentLeavesTheOriginalOrTheCompleteNewFile)
{
    const auto dir = jade::test::out("gltf_kill/x").parent_path();
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto source = jade::test::data("gltf_samples/2CylinderEngine.glb");
    const auto asset = dir / "engine.glb";
    const std::string original = read_all(source);

    // How long one whole in-place bake takes here; the kills are spread over it and past it.
    std::filesystem::copy_file(source, asset);
    const auto t0 = std::chrono::steady_clock::now();
    bake_and_kill(asset, {std::chrono::microseconds(-1)});
    const auto whole = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0);
    ASSERT_NE(read_all(asset), original) << "the uninterrupted bake did not replace the file";

    int old_file = 0, new_file = 0, leftovers = 0;
    std::vector<std::filesystem::path> completed;
    std::vector<Kill> kills;
    for (double f : {0.0, 0.05, 0.4, 0.8, 1.3})
        kills.push_back({std::chrono::microseconds(int64_t(f * double(whole.count())))});
    for (int us : {0, 300, 1000, 3000, 10000}) kills.push_back({std::chrono::microseconds(us), true});
    for (const Kill& kill : kills) {
        SCOPED_TRACE("SIGKILL " + std::to_string(kill.delay.count()) + " us after " +
                     (kill.after_temp ? "the temporary file appeared" : "the start") + "; a whole bake takes " +
                     std::to_string(whole.count()) + " us");
        std::filesystem::remove(asset);
        std::filesystem::copy_file(source, asset);
        bake_and_kill(asset, kill);
        const std::string now = read_all(asset);
        if (now == original) {
            ++old_file;
        } else {
            // Anything else must be the complete new asset.
            ++new_file;
            const GltfFile out = jade::test::read_gltf_file(asset);
            expect_asset_kept(jade::test::read_gltf_file(source), out);
            expect_baked_attributes(out);
            completed.push_back(dir / ("completed_" + std::to_string(new_file) + ".glb"));
            std::filesystem::copy_file(asset, completed.back());
        }
        // A killed writer may leave its temporary file: never under the asset's name.
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            const std::string name = entry.path().filename().string();
            if (name.rfind("engine.glb.tmp-", 0) == 0)
                ++leftovers, std::filesystem::remove(entry.path());
            else
                EXPECT_TRUE(name == "engine.glb" || name.rfind("completed_", 0) == 0) << name;
        }
    }
    std::printf(
        "[ kill     ] whole bake %.0f ms; %d kills left the original, %d the new file, %d temporary files left\n",
        double(whole.count()) / 1000.0, old_file, new_file, leftovers);
    EXPECT_GE(old_file, 1);
    EXPECT_GE(new_file, 1);
    std::string why;
    const auto reports = jade::test::run_gltf_validator(completed, &why);
    if (!reports) GTEST_SKIP() << why;
    ASSERT_EQ(reports->size(), completed.size()) << why;
    for (const auto& r : *reports) EXPECT_TRUE(r.errors == 0 && r.warnings == 0) << r.file;
}

}  // namespace
