// jade fidelity: Jade's shading modes against the committed path-traced references of
// tools/groundtruth (Mitsuba 3, a homogeneous medium behind a rough dielectric): LDR FLIP per
// scene and light, the mean linear radiance over the thin region, and each mode's frame time.
// `--components DIR` writes the separate terms the calibration (tools/groundtruth/fit.py) fits.
#include "commands.hpp"

#include <jade/dev/context.hpp>
#include <jade/dev/io.hpp>
#include <jade/dev/material.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/io.hpp>
#include <jade/render.hpp>

#include "fidelity_modes.hpp"
#include "flip.hpp"
#include "render_setup.hpp"
#include "report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

namespace jade::cli {
namespace {

using json = nlohmann::json;

glm::vec3 vec3_of(const json& j) { return glm::vec3(j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()); }
glm::dvec3 dvec3_of(const json& j)
{
    return glm::dvec3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

json read_json(const std::filesystem::path& path)
{
    std::ifstream f(path);
    if (!f) throw Error(path.string() + ": cannot open");
    try {
        return json::parse(f);
    } catch (const json::exception& e) {
        throw Error(path.string() + ": not valid JSON: " + e.what());
    }
}

/// One committed reference: the scene record, its images and masks.
struct Reference {
    std::string name, set, mesh, light;
    json record;
    dev::LoadedImage image;           // linear (from the EXR)
    flip::Image srgb;                 // the 8-bit PNG, for FLIP
    std::vector<uint8_t> mask, thin;  // object and thin-region masks, 0/1 per pixel
    std::vector<uint8_t> away;        // surfaces facing away from the light, not thin (empty: none given)
};

std::vector<uint8_t> read_mask(const std::filesystem::path& path, int width, int height)
{
    const dev::LoadedImage m = dev::load_image(path);
    if (m.width != width || m.height != height) throw Error(path.string() + ": mask size differs from the reference");
    std::vector<uint8_t> out(size_t(width) * height);
    for (size_t i = 0; i < out.size(); ++i) out[i] = m.rgba[4 * i] > 0.5f ? 1 : 0;
    return out;
}

Reference load_reference(const std::filesystem::path& dir, const std::filesystem::path& record_path)
{
    Reference r;
    r.record = read_json(record_path);
    try {
        r.name = r.record.at("scene"), r.set = r.record.at("set"), r.mesh = r.record.at("mesh"),
        r.light = r.record.at("light_name");
        const json& files = r.record.at("files");
        r.image = dev::load_image(dir / files.at("exr").get<std::string>());
        const dev::LoadedImage png = dev::load_image(dir / files.at("png").get<std::string>());
        r.srgb = flip::from_linear(uint32_t(png.width), uint32_t(png.height), png.rgba.data(), 4);
        r.mask = read_mask(dir / files.at("mask").get<std::string>(), r.image.width, r.image.height);
        r.thin = read_mask(dir / files.at("thin").get<std::string>(), r.image.width, r.image.height);
        if (files.contains("away"))
            r.away = read_mask(dir / files.at("away").get<std::string>(), r.image.width, r.image.height);
    } catch (const json::exception& e) {
        throw Error(record_path.string() + ": " + e.what());
    }
    return r;
}

/// The mean linear RGB over the pixels where `mask` is set (0 when it is empty).
glm::dvec3 region_mean(const std::vector<float>& rgba, const std::vector<uint8_t>& mask)
{
    glm::dvec3 sum(0.0);
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) sum += glm::dvec3(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]), ++n;
    return n ? sum / double(n) : sum;
}

dev::MediumFit fit_from_args(const Args& args)
{
    dev::MediumFit fit;
    if (auto path = args.get("fit")) {
        const json j = read_json(*path);
        try {
            fit.albedo_scale = j.value("albedo_scale", fit.albedo_scale);
            fit.strength = j.value("strength", fit.strength);
            fit.spread_strength = j.value("spread_strength", fit.spread_strength);
            fit.transmission_weight = j.value("transmission_weight", fit.transmission_weight);
            fit.diffusion_weight = j.value("diffusion_weight", fit.diffusion_weight);
            fit.lobe = j.value("lobe", fit.lobe);
            fit.normal_mix = j.value("normal_mix", fit.normal_mix);
            fit.forward_extinction = j.value("forward_extinction", fit.forward_extinction);
        } catch (const json::exception& e) {
            args.fail("--fit " + *path + ": " + e.what());
        }
    }
    return fit;
}

Medium medium_of(const json& record)
{
    const json& m = record.at("medium");
    Medium medium;
    medium.sigma_s = dvec3_of(m.at("sigma_s"));
    medium.sigma_a = dvec3_of(m.at("sigma_a"));
    medium.g = m.at("g"), medium.ior = m.at("ior"), medium.roughness = m.at("roughness");
    return medium;
}

/// The record's light: directional (towards_light, irradiance) or point (position, intensity:
/// irradiance intensity/r² on a surface facing it at distance r, Mitsuba's and Jade's convention).
Light light_of(const json& light)
{
    if (light.value("type", std::string("directional")) == "point")
        return Light::point(vec3_of(light.at("position")), vec3_of(light.at("intensity")));
    return Light::directional(vec3_of(light.at("towards_light")), vec3_of(light.at("irradiance")));
}

/// The poster's model as the comparison draws it: its Gaussian's variance strength · t_m, with
/// the strength the training scenes' fit chose for it (docs/fidelity.md, *Calibration*).
constexpr float kPosterStrength = 0.3f;

/// A mesh baked once per medium and reused by every light of it.
struct BakedMesh {
    TriangleMesh mesh;
    PreparedMesh prepared;
    BakeResult bake;
};

}  // namespace

int cmd_fidelity(int argc, char** argv)
{
    Args args(
        "fidelity",
        [] {
        auto o = device_options();
        for (auto& b : bake_options()) o.push_back(b);
        o.push_back({"references", "DIR", "the committed references (default tools/groundtruth/references)"});
        o.push_back({"root", "DIR", "where the records' mesh paths start (default: three folders above DIR)"});
        o.push_back(
            {"set", "S", "train | validation | regimes (held out: physical media, point lights) | all (default all)"});
        o.push_back({"scene", "TEXT", "only scenes whose name contains TEXT"});
        o.push_back({"no-shadows", "", "the lights are not shadowed by the mesh (default: shadowed); = --shadows off"});
        o.push_back({"shadows", "S", "on | off | both: score each mode with and without shadows (default on)"});
        o.push_back({"modes", "LIST",
                     "comma-separated modes to score (default all: lambert, curvature, tm, default, "
                     "filament, filament-flat, separable, burley)"});
        o.push_back({"fit", "FILE", "JSON of MediumFit values instead of the built-in defaults"});
        o.push_back(eval_option());
        o.push_back(light_path_option());
        o.push_back({"json", "FILE", "write every number as JSON"});
        o.push_back({"markdown", "FILE", "write the tables as Markdown (docs/fidelity.md's)"});
        o.push_back({"images", "DIR", "also save each scene's image per mode as SCENE__MODE.png"});
        o.push_back({"components", "DIR", "also write each scene's separate terms as EXR (for fit.py)"});
        o.push_back(
            {"strengths", "LIST", "with --components: strengths of the diffuse terms (default 0.25,0.5,0.8,1.2,2)"});
        o.push_back({"lobes", "LIST", "with --components: lobe exponents of the transmission terms (default 1,2,4,8)"});
        return o;
        }(),
        argc, argv, 2);
    if (args.flag("help")) {
        std::printf("jade fidelity [options]\n\nRenders every committed path-traced reference scene in each mode, all "
                    "with the albedo\nderived from the scene's medium, and prints LDR FLIP against the reference, "
                    "whole and inside\nthe object, the thin region's mean linear radiance, and the GPU time per mode. "
                    "Modes:\n");
        for (const Mode& m : kModes) std::printf("  %-14s %s\n", m.name, m.what);
        std::printf("\n%s", args.help().c_str());
        return 0;
    }
    const std::filesystem::path dir = args.get_or("references", "tools/groundtruth/references");
    const std::filesystem::path root =
        args.get_or("root", (std::filesystem::absolute(dir) / ".." / ".." / "..").string());
    const std::string set = args.get_or("set", "all"), filter = args.get_or("scene", "");
    if (set != "train" && set != "validation" && set != "regimes" && set != "all")
        args.fail("--set: '" + set + "' is not train, validation, regimes or all");
    const dev::MediumFit fit = fit_from_args(args);
    const std::vector<const Mode*> modes = modes_from_args(args);
    const std::vector<bool> shadows = shadow_states(args);
    BakeSettings bake_settings = bake_settings_from_args(args);
    const auto components = args.get("components"), images = args.get("images");
    if (components) check_output_folder("components", *components);
    if (images) check_output_folder("images", *images);
    auto list = [&](const char* flag, const char* fallback) {
        std::vector<double> v;
        std::stringstream ss(args.get_or(flag, fallback));
        for (std::string t; std::getline(ss, t, ',');) v.push_back(std::stod(t));
        return v;
    };
    const std::vector<double> strengths = list("strengths", "0.25,0.5,0.8,1.2,2"), lobes = list("lobes", "1,2,4,8");

    std::vector<std::filesystem::path> records;
    if (!std::filesystem::is_directory(dir)) throw Error("--references " + dir.string() + ": no such folder");
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const auto name = e.path().filename().string();
        if (e.path().extension() == ".json" && name.find("_masks") == std::string::npos &&
            name.find("silhouette") == std::string::npos && name.find("noise") == std::string::npos &&
            name.find("summary") == std::string::npos)
            records.push_back(e.path());
    }
    std::sort(records.begin(), records.end());

    auto ctx = make_context(args);
    Baker baker(*ctx);
    Renderer renderer(*ctx, renderer_options(args));
    std::map<std::string, BakedMesh> baked;  // key: mesh + medium
    json out = json::array();
    std::printf("%-26s", "scene (LDR FLIP, masked)");
    for (const Mode* m : modes)
        for (bool s : shadows)
            std::printf(" %*s", int(std::max<size_t>(8, column(*m, s).size())), column(*m, s).c_str());
    std::printf("   thin region mean (ref | default)\n");
    for (const auto& path : records) {
        const json peek = read_json(path);
        if (!peek.contains("scene") || !peek.contains("set")) continue;
        if ((set != "all" && peek["set"] != set) || peek["scene"].get<std::string>().find(filter) == std::string::npos)
            continue;
        Reference ref = load_reference(dir, path);
        const json& rec = ref.record;
        const std::string key = rec.at("mesh").get<std::string>() + "/" + rec.at("medium_name").get<std::string>();
        const Medium medium = medium_of(rec);
        const Material material = dev::from_medium(medium, fit, rec.at("medium_name").get<std::string>());
        if (!baked.count(key)) {
            BakedMesh b;
            // The record's path from the repository root, else the same file in JADE_ASSETS.
            std::filesystem::path file = root / rec.at("mesh_file").get<std::string>();
            if (const char* assets = std::getenv("JADE_ASSETS"); assets && !std::filesystem::exists(file))
                file = std::filesystem::path(assets) / file.filename();
            b.mesh = load_mesh(file);
            b.prepared = prepare_mesh(b.mesh);
            b.bake = baker.bake(b.prepared, material, bake_settings);
            baked.emplace(key, std::move(b));
        }
        const BakedMesh& b = baked.at(key);
        renderer.set_mesh(b.prepared, b.bake);
        Camera camera;
        camera.eye = vec3_of(rec.at("camera").at("eye"));
        camera.target = vec3_of(rec.at("camera").at("target"));
        camera.up = vec3_of(rec.at("camera").at("up"));
        camera.fov_y_degrees = rec.at("camera").at("fov_y_degrees").get<float>();
        const std::vector<Light> lights = {light_of(rec.at("light"))};
        RenderSettings rs;
        rs.width = uint32_t(ref.image.width), rs.height = uint32_t(ref.image.height);
        rs.float32 = true;
        json row = {{"scene", ref.name},
                    {"set", ref.set},
                    {"mesh", ref.mesh},
                    {"light", ref.light},
                    {"medium", rec.at("medium_name")}};
        const glm::dvec3 ref_thin = region_mean(ref.image.rgba, ref.thin);
        row["thin_reference"] = {ref_thin.x, ref_thin.y, ref_thin.z};
        if (!ref.away.empty()) {
            const glm::dvec3 away = region_mean(ref.image.rgba, ref.away);
            row["away_reference"] = {away.x, away.y, away.z};
        }
        std::printf("%-26s", ref.name.c_str());
        renderer.set_material(material);
        glm::dvec3 thin_default(0.0);
        for (const Mode* mode_of_column : modes)
            for (const bool shadowed : shadows) {
                const Mode& mode = *mode_of_column;
                const std::string name = column(mode, shadowed);
                rs.mode = mode.mode;
                rs.transmission = mode.transmission;
                rs.shadows = shadowed;
                rs.filament_thickness = mode.filament_thickness;
                // The poster's model alone: no boundary transmittance either.
                Material as_drawn = material;
                as_drawn.boundary_transmittance = mode.transmission;
                if (!mode.transmission) as_drawn.spread_strength = 0.0f, as_drawn.strength = kPosterStrength;
                renderer.set_material(as_drawn);
                RenderedImage img = renderer.render(camera, lights, rs);
                const flip::Image test = flip::from_linear(img.width, img.height, img.rgba.data(), 4);
                const double whole = flip::ldr_flip(ref.srgb, test),
                             masked = flip::ldr_flip(ref.srgb, test, flip::pixels_per_degree(), &ref.mask);
                const glm::dvec3 thin = region_mean(img.rgba, ref.thin);
                row[name] = {{"flip", whole},
                             {"flip_masked", masked},
                             {"gpu_ms", img.gpu_ms},
                             {"thin", {thin.x, thin.y, thin.z}}};
                if (!ref.away.empty()) {
                    const glm::dvec3 away = region_mean(img.rgba, ref.away);
                    row[name]["away"] = {away.x, away.y, away.z};
                }
                if (name == "default") thin_default = thin;
                if (images)
                    save_image(std::filesystem::path(*images) / (ref.name + "__" + name_for_file(name) + ".png"),
                               int(img.width), int(img.height), img.rgba);
                std::printf(" %*.4f", int(std::max<size_t>(8, name.size())), masked);
            }
        std::printf("   %.3f %.3f %.3f | %.3f %.3f %.3f", ref_thin.x, ref_thin.y, ref_thin.z, thin_default.x,
                    thin_default.y, thin_default.z);
        if (row.contains("away_reference") && row.contains("default")) {
            const json &a = row["away_reference"], &d = row["default"]["away"];
            std::printf("   away %.4f %.4f %.4f | %.4f %.4f %.4f", a[0].get<double>(), a[1].get<double>(),
                        a[2].get<double>(), d[0].get<double>(), d[1].get<double>(), d[2].get<double>());
        }
        std::printf("\n");
        std::fflush(stdout);
        out.push_back(row);
        if (!components) continue;
        // The separate terms: diffuse (albedo R_d, albedo_scale 1) per strength, specular, and the
        // ballistic and diffused transmission (weight 1) per lobe with normal_mix 0 and 1; the image
        // is linear in the rest.
        rs.mode = ShadingMode::Tm;
        auto write = [&](const Material& m, bool transmission, const std::string& term) {
            renderer.set_material(m);
            rs.transmission = transmission;
            RenderedImage img = renderer.render(camera, lights, rs);
            save_image(std::filesystem::path(*components) / (ref.name + "__" + term + ".exr"), int(img.width),
                       int(img.height), img.rgba);
        };
        dev::MediumFit unit = fit;
        unit.albedo_scale = 1.0, unit.transmission_weight = 1.0, unit.diffusion_weight = 1.0;
        Material base = dev::from_medium(medium, unit);
        for (double s : strengths) {
            Material m = base;
            m.strength = float(s), m.specular = 0.0f;
            char term[32];
            std::snprintf(term, sizeof term, "diffuse_s%g", s);
            write(m, false, term);
        }
        Material spec = base;
        spec.albedo = glm::vec3(0.0f);
        write(spec, false, "specular");
        for (double n : lobes)
            for (int mix = 0; mix <= 1; ++mix)
                for (int part = 0; part < 2; ++part) {  // ballistic, diffused
                    Material m = spec;
                    m.specular = 0.0f, m.transmission.lobe = float(n), m.transmission.normal_mix = float(mix);
                    (part == 0 ? m.transmission.diffusion_weight : m.transmission.weight) = 0.0f;
                    char term[48];
                    std::snprintf(term, sizeof term, "transmission_%s_n%g_m%d", part == 0 ? "b" : "d", n, mix);
                    write(m, true, term);
                }
        // What the shading reads per pixel, for fitting other transmission models offline: the
        // position (w: coverage), the normal with the first light's path t (w; 0 without) and the
        // baked thickness t̄.
        renderer.set_material(material);
        rs.transmission = true;
        const ShadingInputs in = dev::shading_inputs(renderer, camera, lights, rs);
        std::vector<float> position, normal_path, thickness;
        for (size_t p = 0; p < in.position.size(); ++p) {
            const glm::vec4 x = in.position[p], n = in.normal[p];
            position.insert(position.end(), {x.x, x.y, x.z, x.w});
            normal_path.insert(normal_path.end(), {n.x, n.y, n.z, in.path.empty() ? 0.0f : in.path[p]});
            thickness.insert(thickness.end(), {n.w, n.w, n.w, x.w});
        }
        const auto folder = std::filesystem::path(*components);
        save_image(folder / (ref.name + "__inputs_position.exr"), int(in.width), int(in.height), position);
        save_image(folder / (ref.name + "__inputs_normal_path.exr"), int(in.width), int(in.height), normal_path);
        save_image(folder / (ref.name + "__inputs_thickness.exr"), int(in.width), int(in.height), thickness);
    }
    if (out.empty()) throw Error("--references " + dir.string() + ": no reference scene matched");
    if (auto path = args.get("markdown"))
        dev::write_file_atomically(*path, fidelity_markdown(out, modes, shadows, dev::device_info(*ctx).name));
    if (auto path = args.get("json")) {
        const json doc = {{"fit",
                           {{"albedo_scale", fit.albedo_scale},
                            {"strength", fit.strength},
                            {"spread_strength", fit.spread_strength},
                            {"transmission_weight", fit.transmission_weight},
                            {"diffusion_weight", fit.diffusion_weight},
                            {"lobe", fit.lobe},
                            {"normal_mix", fit.normal_mix},
                            {"forward_extinction", fit.forward_extinction}}},
                          {"scenes", out}};
        dev::write_file_atomically(*path, doc.dump(1));
    }
    return 0;
}

}  // namespace jade::cli
