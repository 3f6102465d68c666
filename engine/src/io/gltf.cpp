// io/gltf.cpp - glTF 2.0 reader (.gltf with embedded or external buffers, and .glb).
//
// tinygltf parses the file (io/gltf_model.cpp); every reference and byte range it does not
// check is checked here or in io/gltf_accessors.cpp before it is read. The default scene (or
// scene 0, or without scenes every root node) is flattened: each mesh instance contributes all
// its triangle primitives, transformed to world space (positions by the node's world matrix,
// normals by its inverse transpose, winding reversed where the matrix mirrors). Skins and morph
// targets are ignored: the bind pose is what is baked.
#include "io/common.hpp"
#include "io/gltf_accessors.hpp"
#include "io/gltf_model.hpp"
#include "io/gltf_translucency.hpp"
#include "io/loaders.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <optional>

namespace jade::io {

namespace {

// ------------------------------------------------------------------------------ the scene --

glm::dmat4 local_transform(const std::string& name, const tinygltf::Node& node, int index)
{
    const std::string subject = "node " + std::to_string(index) + ": ";
    glm::dmat4 m(1.0);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16)
            fail(name, subject + "matrix has " + std::to_string(node.matrix.size()) + " values, not 16");
        m = glm::make_mat4(node.matrix.data());  // both column-major
    } else {
        const auto& t = node.translation;
        const auto& r = node.rotation;
        const auto& s = node.scale;
        if ((!t.empty() && t.size() != 3) || (!r.empty() && r.size() != 4) || (!s.empty() && s.size() != 3))
            fail(name, subject + "translation, rotation or scale has the wrong number of values");
        glm::dquat q = r.empty() ? glm::dquat(1.0, 0.0, 0.0, 0.0) : glm::dquat(r[3], r[0], r[1], r[2]);
        if (!(glm::length(q) > 0.0)) fail(name, subject + "rotation quaternion has zero length");
        m = glm::mat4_cast(glm::normalize(q));  // exporters write quaternions rounded to float
        if (!s.empty())
            m = m * glm::dmat4(glm::dvec4(s[0], 0, 0, 0), glm::dvec4(0, s[1], 0, 0), glm::dvec4(0, 0, s[2], 0),
                               glm::dvec4(0, 0, 0, 1));
        if (!t.empty()) m[3] = glm::dvec4(t[0], t[1], t[2], 1.0);
    }
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) fail(name, subject + "transform is not finite");
    return m;
}

std::vector<int> scene_roots(const std::string& name, const tinygltf::Model& model)
{
    if (!model.scenes.empty()) {
        const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (size_t(scene) >= model.scenes.size())
            fail(name, "default scene " + std::to_string(scene) + " does not exist (" +
                           std::to_string(model.scenes.size()) + " scenes)");
        return model.scenes[size_t(scene)].nodes;
    }
    if (model.defaultScene >= 0)
        fail(name, "default scene " + std::to_string(model.defaultScene) + " does not exist (no scenes)");
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const auto& node : model.nodes)
        for (int c : node.children)
            if (c >= 0 && size_t(c) < is_child.size()) is_child[size_t(c)] = true;
    std::vector<int> roots;
    for (size_t n = 0; n < model.nodes.size(); ++n)
        if (!is_child[n]) roots.push_back(int(n));
    return roots;
}

/// Walks the node trees from `roots` (iteratively: no stack overflow on deep hierarchies) and
/// lists every mesh instance with its world matrix. glTF nodes have at most one parent; a node
/// reached twice is reported as a cycle or as a node with two parents.
std::vector<MeshInstance> mesh_instances(const std::string& name, const tinygltf::Model& model,
                                         const std::vector<int>& roots)
{
    constexpr int kUnvisited = -2, kRoot = -1;
    std::vector<int> parent(model.nodes.size(), kUnvisited);
    struct Pending {
        int node, parent;
        glm::dmat4 parent_world;
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, kRoot, glm::dmat4(1.0)});
    std::vector<MeshInstance> instances;
    while (!stack.empty()) {
        const Pending p = stack.back();
        stack.pop_back();
        auto describe = [](int node) {
            return node == kRoot ? std::string("the scene") : "node " + std::to_string(node);
        };
        if (p.node < 0 || size_t(p.node) >= model.nodes.size())
            fail(name, describe(p.parent) + " refers to node " + std::to_string(p.node) + ", which does not exist");
        const std::string node_name = "node " + std::to_string(p.node);
        if (const int first = parent[size_t(p.node)]; first != kUnvisited) {
            for (int a = p.parent; a >= 0; a = parent[size_t(a)])
                if (a == p.node) fail(name, node_name + " is its own ancestor (the node hierarchy has a cycle)");
            fail(name, node_name + " is reached twice (from " + describe(first) + " and from " + describe(p.parent) +
                           "); glTF nodes have at most one parent");
        }
        parent[size_t(p.node)] = p.parent;
        const auto& node = model.nodes[size_t(p.node)];
        const glm::dmat4 world = p.parent_world * local_transform(name, node, p.node);
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size())
                fail(name, node_name + ": mesh " + std::to_string(node.mesh) + " does not exist");
            instances.push_back({node.mesh, world, p.node});
        }
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back({*it, p.node, world});
    }
    return instances;
}

// ------------------------------------------------------------------------------ primitives --

const char* mode_name(int mode)
{
    static const char* const kNames[] = {"POINTS",    "LINES",          "LINE_LOOP",   "LINE_STRIP",
                                         "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
    return mode >= 0 && mode < 7 ? kNames[mode] : "unknown";
}

/// Collects the world-space triangles of every instance. Normals and the baked attributes are kept
/// only when every primitive has them (they must be one per vertex or absent).
class MeshBuilder {
public:
    MeshBuilder(const std::string& name, const tinygltf::Model& model)
        : name_(name), model_(model), accessors_(name, model)
    {
        mesh_.name = name;
    }

    /// Every triangle primitive of the instance. Points and lines are left out (a baked asset
    /// may carry them); a file with nothing else fails naming the first of them (finish()).
    void add(const MeshInstance& instance)
    {
        const auto& mesh = model_.meshes[size_t(instance.mesh)];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const std::string where =
                "mesh " + std::to_string(instance.mesh) + " primitive " + std::to_string(p) + ": ";
            if (const int mode = mesh.primitives[p].mode; !is_triangle_mode(mode)) {
                if (skipped_.empty())
                    skipped_ = where + "mode " + std::to_string(mode) + " (" + mode_name(mode) +
                               ") is not supported (only triangles)";
                continue;
            }
            add_primitive(where, mesh.primitives[p], instance.world);
        }
    }

    /// Only primitive `p` of the instance (a scene object, io/scene_gltf.cpp).
    void add(const MeshInstance& instance, size_t p)
    {
        add_primitive("mesh " + std::to_string(instance.mesh) + " primitive " + std::to_string(p) + ": ",
                      model_.meshes[size_t(instance.mesh)].primitives[p], instance.world);
    }

    TriangleMesh finish()
    {
        if (mesh_.indices.empty() && !skipped_.empty()) fail(name_, skipped_);
        if (!all_normals_) mesh_.normals.clear();
        if (!all_ao_) mesh_.baked_ao.clear();
        if (!all_tm_) mesh_.baked_tm.clear();
        if (!all_thickness_) mesh_.baked_thickness.clear();
        if (!all_scattering_normal_) mesh_.baked_scattering_normal.clear();
        if (!all_normal_spread_) mesh_.baked_normal_spread.clear();
        return std::move(mesh_);
    }

    /// The JADE_materials_translucency of the first triangle primitive's material, if any, checked.
    std::optional<Material> baked_material() const
    {
        if (first_material_ < 0 || size_t(first_material_) >= model_.materials.size()) return std::nullopt;
        const auto& extensions = model_.materials[size_t(first_material_)].extensions;
        const auto it = extensions.find(kTranslucencyExtension);
        if (it == extensions.end()) return std::nullopt;
        return material_from_translucency(name_, "material " + std::to_string(first_material_), to_json(it->second));
    }

private:
    int attribute(const tinygltf::Primitive& prim, const char* name) const
    {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    }

    void add_primitive(const std::string& where, const tinygltf::Primitive& prim, const glm::dmat4& world)
    {
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            fail(name_, where + "mode " + std::to_string(mode) + " (" + mode_name(mode) +
                            ") is not supported (only triangles)");
        const int position = attribute(prim, "POSITION");
        if (position < 0) fail(name_, where + "has no POSITION attribute");
        const auto positions =
            accessors_.view(where, position, {"POSITION", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}});
        if (!positions.data)
            fail(name_, where + "accessor " + std::to_string(position) + " (POSITION) has no bufferView");
        const size_t base = mesh_.positions.size();
        if (positions.count > kMaxVertices - base)
            fail(name_, where + "more vertices in total than 32-bit indices can address");

        add_vertices(where, prim, positions, world);
        add_triangles(where, prim, mode, positions.count, base, glm::determinant(glm::dmat3(world)) < 0.0);
    }

    void add_vertices(const std::string& where, const tinygltf::Primitive& prim, const AccessorView& positions,
                      const glm::dmat4& world)
    {
        const size_t n = positions.count;
        for (size_t i = 0; i < n; ++i)
            mesh_.positions.push_back(glm::vec3(world * glm::dvec4(glm::dvec3(positions.vec3(i)), 1.0)));

        const glm::dmat3 linear(world);
        const bool invertible = glm::determinant(linear) != 0.0;
        const glm::dmat3 normal_matrix = invertible ? glm::transpose(glm::inverse(linear)) : glm::dmat3(1.0);
        const auto normals = optional_attribute(where, prim, "NORMAL", TINYGLTF_TYPE_VEC3, n, all_normals_);
        if (!invertible) all_normals_ = false;
        // Without a linear transform the normals are copied as stored, so that a file written
        // by save_baked_gltf reads back bit for bit; otherwise they are renormalised.
        const bool keep = linear == glm::dmat3(1.0);
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3 stored = normals ? normals->vec3(i) : glm::vec3(0.0f);
            const glm::dvec3 v = normal_matrix * glm::dvec3(stored);
            const double len = glm::length(v);
            mesh_.normals.push_back(keep ? stored : glm::vec3(len > 0.0 ? v / len : v));
        }
        const auto ao = optional_attribute(where, prim, "_AO", TINYGLTF_TYPE_SCALAR, n, all_ao_);
        for (size_t i = 0; i < n; ++i) mesh_.baked_ao.push_back(ao ? ao->scalar(i) : 0.0f);
        const auto tm = optional_attribute(where, prim, "_TM", TINYGLTF_TYPE_VEC3, n, all_tm_);
        for (size_t i = 0; i < n; ++i) mesh_.baked_tm.push_back(tm ? tm->vec3(i) : glm::vec3(0.0f));
        const auto thickness = optional_attribute(where, prim, "_THICKNESS", TINYGLTF_TYPE_SCALAR, n, all_thickness_);
        for (size_t i = 0; i < n; ++i) mesh_.baked_thickness.push_back(thickness ? thickness->scalar(i) : 0.0f);
        // The scattering normal is a normal: transformed as NORMAL is (and kept as stored alike).
        const auto scattering =
            optional_attribute(where, prim, "_SCATTERING_NORMAL", TINYGLTF_TYPE_VEC3, n, all_scattering_normal_);
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3 stored = scattering ? scattering->vec3(i) : glm::vec3(0.0f);
            const glm::dvec3 v = normal_matrix * glm::dvec3(stored);
            const double len = glm::length(v);
            mesh_.baked_scattering_normal.push_back(keep ? stored : glm::vec3(len > 0.0 ? v / len : v));
        }
        const auto spread =
            optional_attribute(where, prim, "_NORMAL_SPREAD", TINYGLTF_TYPE_VEC3, n, all_normal_spread_);
        for (size_t i = 0; i < n; ++i) mesh_.baked_normal_spread.push_back(spread ? spread->vec3(i) : glm::vec3(0.0f));
        if (!invertible) all_scattering_normal_ = false;
        if (first_material_ == kNotSeen) first_material_ = prim.material;
    }

    /// A float attribute with one value per vertex, or nullopt (clearing `all`) when absent.
    std::optional<AccessorView> optional_attribute(const std::string& where, const tinygltf::Primitive& prim,
                                                   const char* role, int type, size_t vertices, bool& all) const
    {
        const int index = attribute(prim, role);
        if (index < 0) {
            all = false;
            return std::nullopt;
        }
        auto view = accessors_.view(where, index, {role, type, {TINYGLTF_COMPONENT_TYPE_FLOAT}});
        if (view.count != vertices)
            fail(name_, where + "accessor " + std::to_string(index) + " (" + role + ") has " +
                            std::to_string(view.count) + " elements for " + std::to_string(vertices) + " vertices");
        return view;
    }

    /// The primitive's vertex sequence: its indices, checked, or 0..n-1.
    std::vector<uint32_t> corners(const std::string& where, const tinygltf::Primitive& prim, size_t vertices) const
    {
        std::vector<uint32_t> out;
        if (prim.indices < 0) {
            out.resize(vertices);
            for (size_t i = 0; i < vertices; ++i) out[i] = uint32_t(i);
            return out;
        }
        const auto view =
            accessors_.view(where, prim.indices,
                            {"indices",
                             TINYGLTF_TYPE_SCALAR,
                             {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}});
        out.resize(view.count);
        for (size_t i = 0; i < view.count; ++i) {
            out[i] = view.index(i);
            if (out[i] >= vertices)
                fail(name_, where + "accessor " + std::to_string(prim.indices) + " (indices): index " +
                                std::to_string(out[i]) + " out of range for " + std::to_string(vertices) + " vertices");
        }
        return out;
    }

    void add_triangles(const std::string& where, const tinygltf::Primitive& prim, int mode, size_t vertices,
                       size_t base, bool mirrored)
    {
        const auto c = corners(where, prim, vertices);
        std::vector<uint32_t> tris;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (c.size() % 3 != 0)
                fail(name_, where + std::to_string(c.size()) + " vertices for TRIANGLES is not a multiple of 3");
            tris = c;
        } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            append_fan(c, tris);
        } else {
            // Strip triangle i is (p[i], p[i+1+i%2], p[i+2-i%2]): every other one is flipped
            // back to the strip's winding.
            for (size_t i = 0; i + 2 < c.size(); ++i)
                tris.insert(tris.end(), {c[i], c[i + 1 + i % 2], c[i + 2 - i % 2]});
        }
        // Instancing can multiply a small file into a huge mesh: bound it before appending.
        if (tris.size() / 3 > kMaxTriangles - mesh_.indices.size() / 3)
            fail(name_, where + "more than " + std::to_string(kMaxTriangles) + " triangles in total");
        for (size_t t = 0; t < tris.size(); t += 3) {
            // A mirroring transform makes counter-clockwise triangles clockwise: the glTF spec
            // says the sign of the world matrix's determinant decides the winding.
            if (mirrored) std::swap(tris[t + 1], tris[t + 2]);
            for (int k = 0; k < 3; ++k) mesh_.indices.push_back(uint32_t(base + tris[t + size_t(k)]));
        }
    }

    const std::string& name_;
    const tinygltf::Model& model_;
    AccessorReader accessors_;
    TriangleMesh mesh_;
    bool all_normals_ = true, all_ao_ = true, all_tm_ = true, all_thickness_ = true;
    bool all_scattering_normal_ = true, all_normal_spread_ = true;
    static constexpr int kNotSeen = -2;
    int first_material_ = kNotSeen;  ///< the first triangle primitive's material (-1: none)
    std::string skipped_;            ///< why the first non-triangle primitive was left out
};

}  // namespace

std::vector<MeshInstance> scene_mesh_instances(const std::string& name, const tinygltf::Model& model)
{
    return mesh_instances(name, model, scene_roots(name, model));
}

bool is_triangle_mode(int mode)
{
    return mode < 0 || mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

TriangleMesh read_gltf_primitive(const std::string& name, const tinygltf::Model& model, int mesh, size_t primitive,
                                 const glm::dmat4& world)
{
    MeshBuilder builder(name, model);
    builder.add({mesh, world, -1}, primitive);
    return builder.finish();
}

TriangleMesh read_gltf(const std::filesystem::path& path, const std::string& name, const std::string& bytes,
                       bool binary, const ReadOptions& options)
{
    if (bytes.empty()) fail(name, "file is empty");
    const auto model = parse_gltf(path, name, bytes, binary, options);
    check_required_extensions(name, model);
    MeshBuilder builder(name, model);
    for (const auto& instance : scene_mesh_instances(name, model)) builder.add(instance);
    TriangleMesh mesh = builder.finish();
    if (options.baked_material) *options.baked_material = builder.baked_material();
    return mesh;
}

std::vector<GltfPrimitive> read_gltf_primitives(const std::string& name, const tinygltf::Model& model)
{
    check_required_extensions(name, model);
    std::vector<GltfPrimitive> out;
    for (const auto& instance : scene_mesh_instances(name, model)) {
        const auto& mesh = model.meshes[size_t(instance.mesh)];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            if (!is_triangle_mode(mesh.primitives[p].mode)) continue;  // points and lines are no objects
            MeshBuilder builder(name, model);
            builder.add(instance, p);
            out.push_back({builder.finish(), instance.node, instance.mesh, int(p), mesh.primitives[p].material});
        }
    }
    return out;
}

}  // namespace jade::io
