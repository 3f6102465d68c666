// io/gltf_animation.cpp - jade::load_animated_gltf: one mesh of a glTF file with its skin,
// morph targets, node hierarchy and animations, for jade/deform.hpp.
//
// The animated mesh is the first node in file order that has a mesh; all its triangle
// primitives (TRIANGLES mode) are merged, in the mesh's own coordinates (the pose applies the
// node's transform, or the joints' for a skinned mesh). Every reference, count and key time is
// checked before use; a bad file throws jade::Error naming the element.
#include <jade/deform.hpp>
#include <jade/io.hpp>

#include "deform/animation.hpp"
#include "io/common.hpp"
#include "io/gltf_accessors.hpp"
#include "io/gltf_model.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <new>

namespace jade {

namespace {

using io::fail;

struct Reader {
    const std::string& name;
    const tinygltf::Model& model;
    io::AccessorReader accessors;

    Reader(const std::string& n, const tinygltf::Model& m) : name(n), model(m), accessors(n, m) {}

    /// `count` floats per element of a FLOAT accessor of type `type`, all finite.
    std::vector<float> floats(const std::string& where, int index, const char* role, int type) const
    {
        const auto v = accessors.view(where, index, {role, type, {TINYGLTF_COMPONENT_TYPE_FLOAT}});
        const size_t width = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
        std::vector<float> out(v.count * width, 0.0f);
        if (v.data)
            for (size_t i = 0; i < v.count; ++i)
                std::memcpy(out.data() + i * width, v.data + i * v.stride, width * sizeof(float));
        for (size_t i = 0; i < out.size(); ++i)
            if (!std::isfinite(out[i]))
                fail(name, where + "accessor " + std::to_string(index) + " (" + role + "): element " +
                               std::to_string(i / width) + " is not finite");
        return out;
    }

    int attribute(const tinygltf::Primitive& p, const char* key) const
    {
        auto it = p.attributes.find(key);
        return it == p.attributes.end() ? -1 : it->second;
    }
};

AnimatedNode read_node(const std::string& name, const tinygltf::Node& node, int index)
{
    const std::string subject = "node " + std::to_string(index) + ": ";
    AnimatedNode n;
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16)
            fail(name, subject + "matrix has " + std::to_string(node.matrix.size()) + " values, not 16");
        n.has_matrix = true;
        n.matrix = glm::mat4(glm::make_mat4(node.matrix.data()));
    }
    const auto& t = node.translation;
    const auto& r = node.rotation;
    const auto& s = node.scale;
    if ((!t.empty() && t.size() != 3) || (!r.empty() && r.size() != 4) || (!s.empty() && s.size() != 3))
        fail(name, subject + "translation, rotation or scale has the wrong number of values");
    if (!t.empty()) n.translation = glm::vec3(float(t[0]), float(t[1]), float(t[2]));
    if (!r.empty()) {
        n.rotation = glm::quat(float(r[3]), float(r[0]), float(r[1]), float(r[2]));
        if (!(glm::length(n.rotation) > 0.0f)) fail(name, subject + "rotation quaternion has zero length");
        n.rotation = glm::normalize(n.rotation);
    }
    if (!s.empty()) n.scale = glm::vec3(float(s[0]), float(s[1]), float(s[2]));
    const glm::mat4 m = deform::local_transform(n);
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k)
            if (!std::isfinite(m[c][k])) fail(name, subject + "transform is not finite");
    return n;
}

void read_nodes(const std::string& name, const tinygltf::Model& model, AnimatedMesh& out)
{
    out.nodes.resize(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) out.nodes[i] = read_node(name, model.nodes[i], int(i));
    for (size_t i = 0; i < model.nodes.size(); ++i)
        for (int c : model.nodes[i].children) {
            if (c < 0 || size_t(c) >= model.nodes.size())
                fail(name,
                     "node " + std::to_string(i) + " refers to child " + std::to_string(c) + ", which does not exist");
            if (out.nodes[size_t(c)].parent >= 0)
                fail(name, "node " + std::to_string(c) + " has two parents (nodes " +
                               std::to_string(out.nodes[size_t(c)].parent) + " and " + std::to_string(i) + ")");
            out.nodes[size_t(c)].parent = int(i);
        }
    // With one parent each, a cycle is a chain longer than the node count.
    for (size_t i = 0; i < out.nodes.size(); ++i) {
        size_t steps = 0;
        for (int a = out.nodes[i].parent; a >= 0; a = out.nodes[size_t(a)].parent)
            if (++steps > out.nodes.size())
                fail(name, "node " + std::to_string(i) + " is its own ancestor (the hierarchy has a cycle)");
    }
}

/// `_AO`, `_TM` and `_THICKNESS` (jade bake), kept when every primitive has them, as load_mesh does.
struct BakedReader {
    bool all_ao = true, all_tm = true, all_thickness = true;

    void add(const Reader& r, const std::string& where, const tinygltf::Primitive& prim, size_t n, TriangleMesh& mesh)
    {
        auto read = [&](const char* role, int type, bool& all) {
            const int index = r.attribute(prim, role);
            std::vector<float> v;
            const size_t width = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
            if (index >= 0) v = r.floats(where, index, role, type);
            if (index >= 0 && v.size() != n * width)
                fail(r.name, where + "accessor " + std::to_string(index) + " (" + role + ") has " +
                                 std::to_string(v.size() / width) + " elements for " + std::to_string(n) + " vertices");
            if (index < 0) all = false, v.assign(n * width, 0.0f);
            return v;
        };
        const auto ao = read("_AO", TINYGLTF_TYPE_SCALAR, all_ao);
        const auto tm = read("_TM", TINYGLTF_TYPE_VEC3, all_tm);
        const auto thickness = read("_THICKNESS", TINYGLTF_TYPE_SCALAR, all_thickness);
        mesh.baked_ao.insert(mesh.baked_ao.end(), ao.begin(), ao.end());
        for (size_t i = 0; i < n; ++i) mesh.baked_tm.emplace_back(tm[3 * i], tm[3 * i + 1], tm[3 * i + 2]);
        mesh.baked_thickness.insert(mesh.baked_thickness.end(), thickness.begin(), thickness.end());
    }

    void finish(TriangleMesh& mesh) const
    {
        if (!all_ao) mesh.baked_ao.clear();
        if (!all_tm) mesh.baked_tm.clear();
        if (!all_thickness) mesh.baked_thickness.clear();
    }
};

void read_mesh(const Reader& r, int mesh_index, bool skinned, AnimatedMesh& out)
{
    const auto& mesh = r.model.meshes[size_t(mesh_index)];
    out.mesh.name = r.name;
    size_t targets = 0;
    BakedReader baked;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const auto& prim = mesh.primitives[p];
        const std::string where = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p) + ": ";
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES)
            fail(r.name, where + "mode " + std::to_string(mode) + " is not supported for animation (only TRIANGLES)");
        const int pos = r.attribute(prim, "POSITION");
        if (pos < 0) fail(r.name, where + "has no POSITION attribute");
        const auto positions = r.floats(where, pos, "POSITION", TINYGLTF_TYPE_VEC3);
        const size_t n = positions.size() / 3, base = out.mesh.positions.size();
        if (n > io::kMaxVertices - base) fail(r.name, where + "more vertices in total than 32-bit indices can address");
        for (size_t i = 0; i < n; ++i)
            out.mesh.positions.emplace_back(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
        baked.add(r, where, prim, n, out.mesh);

        if (p == 0) targets = prim.targets.size(), out.morph_deltas.resize(targets);
        if (prim.targets.size() != targets)
            fail(r.name, where + "has " + std::to_string(prim.targets.size()) + " morph targets, primitive 0 has " +
                             std::to_string(targets));
        for (size_t k = 0; k < targets; ++k) {
            auto it = prim.targets[k].find("POSITION");
            std::vector<float> d(3 * n, 0.0f);
            if (it != prim.targets[k].end()) {
                d = r.floats(where + "target " + std::to_string(k) + ": ", it->second, "POSITION", TINYGLTF_TYPE_VEC3);
                if (d.size() != 3 * n)
                    fail(r.name, where + "target " + std::to_string(k) + " has " + std::to_string(d.size() / 3) +
                                     " positions for " + std::to_string(n) + " vertices");
            }
            for (size_t i = 0; i < n; ++i) out.morph_deltas[k].emplace_back(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
        }

        if (skinned) {
            const int j = r.attribute(prim, "JOINTS_0"), w = r.attribute(prim, "WEIGHTS_0");
            if (j < 0 || w < 0)
                fail(r.name, where + "the node has a skin but the primitive has no JOINTS_0 and WEIGHTS_0");
            const auto jv =
                r.accessors.view(where, j,
                                 {"JOINTS_0",
                                  TINYGLTF_TYPE_VEC4,
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}});
            const auto wv = r.accessors.view(where, w,
                                             {"WEIGHTS_0",
                                              TINYGLTF_TYPE_VEC4,
                                              {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                               TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}});
            if (jv.count != n || wv.count != n)
                fail(r.name,
                     where + "JOINTS_0 or WEIGHTS_0 has not one element per vertex (" + std::to_string(n) + ")");
            for (size_t i = 0; i < n; ++i) {
                glm::uvec4 ji(0);
                glm::vec4 wi(0.0f);
                for (int c = 0; c < 4; ++c) {
                    if (jv.data) {
                        const unsigned char* q = jv.data + i * jv.stride;
                        if (jv.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
                            ji[c] = q[c];
                        else {
                            uint16_t s;
                            std::memcpy(&s, q + 2 * c, 2);
                            ji[c] = s;
                        }
                    }
                    if (wv.data) {
                        const unsigned char* q = wv.data + i * wv.stride;
                        if (wv.component == TINYGLTF_COMPONENT_TYPE_FLOAT)
                            std::memcpy(&wi[c], q + 4 * c, 4);
                        else if (wv.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
                            wi[c] = float(q[c]) / 255.0f;
                        else {
                            uint16_t s;
                            std::memcpy(&s, q + 2 * c, 2);
                            wi[c] = float(s) / 65535.0f;
                        }
                    }
                    if (!std::isfinite(wi[c]) || wi[c] < 0.0f)
                        fail(r.name, where + "WEIGHTS_0 of vertex " + std::to_string(i) + " is negative or not finite");
                    if (wi[c] > 0.0f && ji[c] >= out.joints.size())
                        fail(r.name, where + "JOINTS_0 of vertex " + std::to_string(i) + " names joint " +
                                         std::to_string(ji[c]) + " of a skin with " +
                                         std::to_string(out.joints.size()));
                    if (wi[c] == 0.0f) ji[c] = 0;  // unused slots may hold anything
                }
                out.joint_indices.push_back(ji);
                out.joint_weights.push_back(wi);
            }
        }

        std::vector<uint32_t> corners;
        if (prim.indices < 0) {
            for (size_t i = 0; i < n; ++i) corners.push_back(uint32_t(i));
        } else {
            const auto iv =
                r.accessors.view(where, prim.indices,
                                 {"indices",
                                  TINYGLTF_TYPE_SCALAR,
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}});
            for (size_t i = 0; i < iv.count; ++i) {
                const uint32_t v = iv.index(i);
                if (v >= n)
                    fail(r.name,
                         where + "index " + std::to_string(v) + " out of range for " + std::to_string(n) + " vertices");
                corners.push_back(v);
            }
        }
        if (corners.size() % 3 != 0)
            fail(r.name, where + std::to_string(corners.size()) + " vertices for TRIANGLES is not a multiple of 3");
        for (uint32_t c : corners) out.mesh.indices.push_back(uint32_t(base + c));
    }
    baked.finish(out.mesh);
    out.default_weights.assign(targets, 0.0f);
    const auto& w = r.model.nodes[size_t(out.mesh_node)].weights.empty() ? mesh.weights
                                                                         : r.model.nodes[size_t(out.mesh_node)].weights;
    if (!w.empty() && w.size() != targets)
        fail(r.name, "mesh " + std::to_string(mesh_index) + ": " + std::to_string(w.size()) + " default weights for " +
                         std::to_string(targets) + " morph targets");
    for (size_t k = 0; k < w.size(); ++k) out.default_weights[k] = float(w[k]);
}

void read_skin(const Reader& r, int skin_index, AnimatedMesh& out)
{
    if (skin_index < 0 || size_t(skin_index) >= r.model.skins.size())
        fail(r.name,
             "node " + std::to_string(out.mesh_node) + ": skin " + std::to_string(skin_index) + " does not exist");
    const auto& skin = r.model.skins[size_t(skin_index)];
    const std::string where = "skin " + std::to_string(skin_index) + ": ";
    if (skin.joints.empty()) fail(r.name, where + "has no joints");
    for (int j : skin.joints) {
        if (j < 0 || size_t(j) >= r.model.nodes.size())
            fail(r.name, where + "joint node " + std::to_string(j) + " does not exist");
        out.joints.push_back(j);
    }
    out.inverse_bind.assign(out.joints.size(), glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
        const auto m = r.floats(where, skin.inverseBindMatrices, "inverseBindMatrices", TINYGLTF_TYPE_MAT4);
        if (m.size() != 16 * out.joints.size())
            fail(r.name, where + std::to_string(m.size() / 16) + " inverse bind matrices for " +
                             std::to_string(out.joints.size()) + " joints");
        for (size_t j = 0; j < out.joints.size(); ++j) out.inverse_bind[j] = glm::make_mat4(m.data() + 16 * j);
    }
    out.skinned = true;
}

void read_animations(const Reader& r, AnimatedMesh& out)
{
    for (size_t a = 0; a < r.model.animations.size(); ++a) {
        const auto& anim = r.model.animations[a];
        Animation result;
        result.name = anim.name.empty() ? "animation " + std::to_string(a) : anim.name;
        for (size_t c = 0; c < anim.channels.size(); ++c) {
            const auto& ch = anim.channels[c];
            const std::string where = "animation " + std::to_string(a) + " channel " + std::to_string(c) + ": ";
            if (ch.target_node < 0 || size_t(ch.target_node) >= r.model.nodes.size())
                fail(r.name, where + "target node " + std::to_string(ch.target_node) + " does not exist");
            if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
                fail(r.name, where + "sampler " + std::to_string(ch.sampler) + " does not exist");
            AnimationChannel out_ch;
            out_ch.node = ch.target_node;
            int type = TINYGLTF_TYPE_VEC3;
            if (ch.target_path == "translation")
                out_ch.path = AnimationPath::Translation, out_ch.width = 3;
            else if (ch.target_path == "rotation")
                out_ch.path = AnimationPath::Rotation, out_ch.width = 4, type = TINYGLTF_TYPE_VEC4;
            else if (ch.target_path == "scale")
                out_ch.path = AnimationPath::Scale, out_ch.width = 3;
            else if (ch.target_path == "weights") {
                out_ch.path = AnimationPath::Weights, type = TINYGLTF_TYPE_SCALAR;
                out_ch.width = uint32_t(ch.target_node == out.mesh_node ? out.morph_deltas.size() : 0);
                if (out_ch.width == 0) continue;  // weights of a mesh we do not animate
            } else {
                continue;  // "pointer" and extension paths: not animated here
            }
            if (out_ch.path != AnimationPath::Weights && out.nodes[size_t(ch.target_node)].has_matrix)
                fail(r.name, where + "animates node " + std::to_string(ch.target_node) +
                                 ", which has a matrix (glTF forbids this)");
            const auto& s = anim.samplers[size_t(ch.sampler)];
            if (s.interpolation.empty() || s.interpolation == "LINEAR")
                out_ch.interpolation = Interpolation::Linear;
            else if (s.interpolation == "STEP")
                out_ch.interpolation = Interpolation::Step;
            else if (s.interpolation == "CUBICSPLINE")
                out_ch.interpolation = Interpolation::CubicSpline;
            else
                fail(r.name, where + "interpolation '" + io::printable(s.interpolation) +
                                 "' is not LINEAR, STEP or CUBICSPLINE");
            out_ch.times = r.floats(where, s.input, "sampler input", TINYGLTF_TYPE_SCALAR);
            out_ch.values = r.floats(where, s.output, "sampler output", type);
            if (out_ch.times.empty()) fail(r.name, where + "the sampler has no keys");
            for (size_t k = 1; k < out_ch.times.size(); ++k)
                if (!(out_ch.times[k] > out_ch.times[k - 1]))
                    fail(r.name, where + "key times are not strictly increasing at key " + std::to_string(k));
            const size_t per_key = out_ch.width * (out_ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
            if (out_ch.values.size() != out_ch.times.size() * per_key)
                fail(r.name, where + std::to_string(out_ch.values.size()) + " output values for " +
                                 std::to_string(out_ch.times.size()) + " keys, expected " +
                                 std::to_string(out_ch.times.size() * per_key));
            result.channels.push_back(std::move(out_ch));
        }
        out.animations.push_back(std::move(result));
    }
}

AnimatedMesh read_animated(const std::filesystem::path& path, const std::string& name, const ReadOptions& options)
{
    const auto ext = io::lower_extension(path);
    if (ext != ".gltf" && ext != ".glb")
        fail(name, "animated meshes are read from glTF (.gltf, .glb), not '" + ext + "'");
    const std::string bytes = io::read_file(path);
    if (bytes.empty()) fail(name, "file is empty");
    const auto model = io::parse_gltf(path, name, bytes, ext == ".glb", options);
    io::check_required_extensions(name, model);
    Reader r(name, model);
    AnimatedMesh out;
    read_nodes(name, model, out);
    for (size_t i = 0; i < model.nodes.size() && out.mesh_node < 0; ++i)
        if (model.nodes[i].mesh >= 0) out.mesh_node = int(i);
    if (out.mesh_node < 0) fail(name, "no node has a mesh");
    const auto& node = model.nodes[size_t(out.mesh_node)];
    if (size_t(node.mesh) >= model.meshes.size())
        fail(name, "node " + std::to_string(out.mesh_node) + ": mesh " + std::to_string(node.mesh) + " does not exist");
    if (node.skin >= 0) read_skin(r, node.skin, out);
    read_mesh(r, node.mesh, node.skin >= 0, out);
    read_animations(r, out);
    io::validate_loaded(out.mesh);
    return out;
}

}  // namespace

AnimatedMesh load_animated_gltf(const std::filesystem::path& path, const ReadOptions& options)
{
    const auto name = io::display_name(path);
    return io::naming_file(name, [&] { return read_animated(path, name, options); });
}

}  // namespace jade
