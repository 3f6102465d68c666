// io/scene_gltf.cpp - jade::load_scene: a glTF file as a Jade scene, and dev::cached_bakes().
//
// Objects: one per triangle primitive of each mesh instance (io/gltf.cpp read_gltf_primitives),
// in world space, with the material as io/gltf_materials.cpp maps it (docs/scene.md has the
// table). Node extras {"jade": {"deform": "bend"}} (or twist, squash, wave; optional "axis"
// 0..2) make the node's objects deforming, with ProceduralDeformer::fit.
#include <jade/dev/cache.hpp>
#include <jade/dev/names.hpp>
#include <jade/io.hpp>
#include <jade/scene.hpp>

#include "io/common.hpp"
#include "io/gltf_materials.hpp"
#include "io/gltf_model.hpp"

#include <jade/error.hpp>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <tuple>

namespace jade {
namespace {

/// The node's {"jade": {"deform": ...}} extras, fitted to the object's mesh.
std::optional<ProceduralDeformer> node_deformer(const std::string& file, const tinygltf::Node& node, int index,
                                                const TriangleMesh& mesh, std::vector<std::string>* warnings)
{
    if (!node.extras.Has("jade")) return std::nullopt;
    const tinygltf::Value& j = node.extras.Get("jade");
    auto warn = [&](const std::string& what) {
        if (warnings) warnings->push_back(file + ": node " + std::to_string(index) + ": " + what);
    };
    if (!j.IsObject() || !j.Has("deform")) return std::nullopt;
    const tinygltf::Value& d = j.Get("deform");
    if (!d.IsString()) {
        warn("extras.jade.deform is not a string; the node is static");
        return std::nullopt;
    }
    DeformerKind kind;
    try {
        kind = dev::parse_deformer(d.Get<std::string>());
    } catch (const Error& e) {
        warn(std::string("extras.jade.deform: ") + e.what() + "; the node is static");
        return std::nullopt;
    }
    uint32_t axis = 1;
    if (j.Has("axis")) {
        const tinygltf::Value& a = j.Get("axis");
        if (a.IsNumber() && (a.GetNumberAsDouble() == 0 || a.GetNumberAsDouble() == 1 || a.GetNumberAsDouble() == 2))
            axis = uint32_t(a.GetNumberAsDouble());
        else
            warn("extras.jade.axis is not 0, 1 or 2; 1 (y) used");
    }
    return ProceduralDeformer::fit(kind, prepare_mesh(mesh), axis);
}

// The rotation R with to[i] = R (from[i] − from[0]) + to[0] for every vertex (within 1e-5 of the
// mesh's extent), if there is one: the frame of three well-spread vertices on each side, checked
// on all. None where the two differ by more than a rigid motion (a scale, a shear, other vertices).
std::optional<glm::mat3> rigid_rotation(std::span<const glm::vec3> from, std::span<const glm::vec3> to)
{
    if (from.size() != to.size() || from.size() < 3) return std::nullopt;
    size_t a = 0, b = 0;
    for (size_t i = 1; i < from.size(); ++i)
        if (glm::length(from[i] - from[0]) > glm::length(from[a] - from[0])) a = i;
    const glm::dvec3 ea = glm::dvec3(from[a] - from[0]);
    double best = 0.0;
    for (size_t i = 1; i < from.size(); ++i)
        if (const double c = glm::length(glm::cross(ea, glm::dvec3(from[i] - from[0]))); c > best) best = c, b = i;
    const double extent = glm::length(ea);
    if (!(extent > 0.0) || !(best > 1e-3 * extent * extent)) return std::nullopt;  // collinear: no frame
    auto frame = [&](std::span<const glm::vec3> p) {
        const glm::dvec3 x = glm::normalize(glm::dvec3(p[a] - p[0]));
        const glm::dvec3 z = glm::normalize(glm::cross(x, glm::dvec3(p[b] - p[0])));
        return glm::dmat3(x, glm::cross(z, x), z);
    };
    const glm::dmat3 r = frame(to) * glm::transpose(frame(from));
    for (size_t i = 0; i < from.size(); ++i)
        if (!(glm::length(r * glm::dvec3(from[i] - from[0]) + glm::dvec3(to[0]) - glm::dvec3(to[i])) <= 1e-5 * extent))
            return std::nullopt;
    return glm::mat3(r);
}

}  // namespace

Scene load_scene(const std::filesystem::path& path, std::vector<std::string>* warnings, const ReadOptions& options)
{
    const std::string name = io::display_name(path);
    return io::naming_file(name, [&] {
        const auto ext = io::lower_extension(path);
        if (ext != ".gltf" && ext != ".glb") io::fail(name, "a scene file must be .gltf or .glb, not '" + ext + "'");
        const std::string bytes = io::read_file(path);
        if (bytes.empty()) io::fail(name, "file is empty");
        const tinygltf::Model model = io::parse_gltf(path, name, bytes, ext == ".glb", options);
        Scene scene;
        scene.name = name;
        io::MaterialMapper mapper(name, model, warnings);
        std::vector<std::optional<Material>> materials(model.materials.size());
        std::optional<Material> no_material;
        // The first object of each (mesh, primitive, material): later instances that are rigid
        // copies of it share its bake (SceneObject::instance_of).
        std::map<std::tuple<int, int, int>, uint32_t> first_instance;
        for (io::GltfPrimitive& p : io::read_gltf_primitives(name, model)) {
            io::validate_loaded(p.mesh);
            if (p.material >= int(model.materials.size()))
                io::fail(name, "mesh " + std::to_string(p.mesh_index) + " primitive " + std::to_string(p.primitive) +
                                   ": material " + std::to_string(p.material) + " does not exist (" +
                                   std::to_string(model.materials.size()) + " materials)");
            auto& slot = p.material < 0 ? no_material : materials.at(size_t(p.material));
            if (!slot) slot = mapper.map(p.material);  // once per material: warnings once
            const auto& node = model.nodes[size_t(p.node)];
            SceneObject o;
            o.name =
                (node.name.empty() ? "node " + std::to_string(p.node) : node.name) + "/" + std::to_string(p.primitive);
            o.material = *slot;
            o.deformer = node_deformer(name, node, p.node, p.mesh, warnings);
            o.mesh = std::move(p.mesh);
            o.mesh.name = name + ": " + o.name;
            const auto key = std::make_tuple(p.mesh_index, p.primitive, p.material);
            if (auto it = first_instance.find(key); it != first_instance.end()) {
                const SceneObject& first = scene.objects[it->second];
                if (!o.deformer && !first.deformer)
                    if (auto r = rigid_rotation(first.mesh.positions, o.mesh.positions))
                        o.instance_of = {it->second, *r, o.mesh.positions[0] - *r * first.mesh.positions[0]};
            } else {
                first_instance.emplace(key, uint32_t(scene.objects.size()));
            }
            scene.objects.push_back(std::move(o));
        }
        if (scene.objects.empty()) io::fail(name, "the default scene has no triangle primitives");
        return scene;
    });
}

StaticBakeSource dev::cached_bakes(const BakeCache& cache)
{
    StaticBakeSource s;
    s.lookup = [&cache](const PreparedMesh& mesh, const Material& material, const BakeSettings& settings) {
        const uint64_t key = bake_key(mesh, material, settings);
        return StaticBakeSource::Lookup{key, cache.load(key, mesh.vertex_count()).has_value()};
    };
    s.bake =
        [&cache](Context& context, const PreparedMesh& mesh, const Material& material, const BakeSettings& settings) {
        return bake_with_cache(context, cache, mesh, material, settings);
    };
    return s;
}

}  // namespace jade
