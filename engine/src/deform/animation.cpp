// deform/animation.cpp - glTF animation sampling and skinning matrices, on the CPU (a few
// nodes per frame); the per-vertex work is shaders/deform_skin.comp.
#include "deform/animation.hpp"

#include <jade/deform.hpp>
#include <jade/error.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace jade {

namespace {

/// Shortest-arc spherical interpolation of unit quaternions (x, y, z, w), in double.
void slerp(const float* q0, const float* q1, double s, float* out)
{
    double a[4], b[4], dot = 0.0;
    for (int c = 0; c < 4; ++c) a[c] = q0[c], b[c] = q1[c], dot += a[c] * b[c];
    if (dot < 0.0) {  // q and -q are the same rotation: take the short way
        for (double& x : b) x = -x;
        dot = -dot;
    }
    double wa, wb;
    if (dot > 0.9995) {  // nearly equal: nlerp (slerp's sin θ would divide by ~0)
        wa = 1.0 - s, wb = s;
    } else {
        const double theta = std::acos(std::min(dot, 1.0));
        wa = std::sin((1.0 - s) * theta) / std::sin(theta);
        wb = std::sin(s * theta) / std::sin(theta);
    }
    double r[4], len = 0.0;
    for (int c = 0; c < 4; ++c) r[c] = wa * a[c] + wb * b[c], len += r[c] * r[c];
    len = std::sqrt(len);
    for (int c = 0; c < 4; ++c) out[c] = float(len > 0.0 ? r[c] / len : r[c]);
}

}  // namespace

std::vector<float> deform::sample(const AnimationChannel& channel, double t)
{
    const std::vector<float>&times = channel.times, &values = channel.values;
    const Interpolation interpolation = channel.interpolation;
    const size_t w = channel.width, keys = times.size();
    std::vector<float> out(w, 0.0f);
    if (keys == 0) return out;
    const bool cubic = interpolation == Interpolation::CubicSpline;
    // Element e of key k: its value (the middle of the three cubic-spline elements).
    auto value = [&](size_t k) { return values.data() + (cubic ? (3 * k + 1) : k) * w; };
    if (t <= times.front() || keys == 1) return std::vector<float>(value(0), value(0) + w);
    if (t >= times.back()) return std::vector<float>(value(keys - 1), value(keys - 1) + w);
    const size_t k = size_t(std::upper_bound(times.begin(), times.end(), float(t)) - times.begin()) - 1;
    const double t0 = times[k], dt = double(times[k + 1]) - t0, s = (t - t0) / dt;
    const bool rotation = channel.path == AnimationPath::Rotation;
    switch (interpolation) {
    case Interpolation::Step: return std::vector<float>(value(k), value(k) + w);
    case Interpolation::Linear:
        if (rotation)
            slerp(value(k), value(k + 1), s, out.data());
        else
            for (size_t c = 0; c < w; ++c) out[c] = float((1.0 - s) * value(k)[c] + s * value(k + 1)[c]);
        return out;
    case Interpolation::CubicSpline: {
        const float* v0 = value(k);
        const float* b0 = values.data() + (3 * k + 2) * w;  // out-tangent of key k
        const float* v1 = value(k + 1);
        const float* a1 = values.data() + (3 * (k + 1)) * w;  // in-tangent of key k + 1
        const double s2 = s * s, s3 = s2 * s;
        double len = 0.0;
        std::vector<double> r(w);
        for (size_t c = 0; c < w; ++c) {
            r[c] = (2 * s3 - 3 * s2 + 1) * v0[c] + dt * (s3 - 2 * s2 + s) * b0[c] + (-2 * s3 + 3 * s2) * v1[c] +
                   dt * (s3 - s2) * a1[c];
            len += r[c] * r[c];
        }
        len = std::sqrt(len);
        for (size_t c = 0; c < w; ++c) out[c] = float(rotation && len > 0.0 ? r[c] / len : r[c]);
        return out;
    }
    }
    return out;
}

double Animation::duration() const
{
    double d = 0.0;
    for (const auto& c : channels)
        if (!c.times.empty()) d = std::max(d, double(c.times.back()));
    return d;
}

glm::mat4 deform::local_transform(const AnimatedNode& node)
{
    if (node.has_matrix) return node.matrix;
    glm::mat4 m = glm::mat4_cast(node.rotation);
    m[0] *= node.scale.x, m[1] *= node.scale.y, m[2] *= node.scale.z;
    m[3] = glm::vec4(node.translation, 1.0f);
    return m;
}

Pose evaluate_pose(const AnimatedMesh& mesh, size_t animation, double t)
{
    std::vector<AnimatedNode> nodes = mesh.nodes;
    Pose pose;
    pose.morph_weights = mesh.default_weights;
    if (animation < mesh.animations.size()) {
        for (const auto& ch : mesh.animations[animation].channels) {
            if (ch.node < 0 || size_t(ch.node) >= nodes.size()) continue;  // checked by the loader
            const auto v = deform::sample(ch, t);
            auto& n = nodes[size_t(ch.node)];
            switch (ch.path) {
            case AnimationPath::Translation: n.translation = glm::vec3(v[0], v[1], v[2]); break;
            case AnimationPath::Rotation: n.rotation = glm::quat(v[3], v[0], v[1], v[2]); break;
            case AnimationPath::Scale: n.scale = glm::vec3(v[0], v[1], v[2]); break;
            case AnimationPath::Weights:
                if (ch.node == mesh.mesh_node)
                    for (size_t k = 0; k < std::min(v.size(), pose.morph_weights.size()); ++k)
                        pose.morph_weights[k] = v[k];
                break;
            }
        }
    }
    // World matrices; the loader checked the hierarchy is a forest. Iterative over the parent
    // chain so that a deep hierarchy cannot overflow the stack.
    std::vector<glm::mat4> world(nodes.size());
    std::vector<bool> done(nodes.size(), false);
    std::vector<size_t> chain;
    for (size_t n = 0; n < nodes.size(); ++n) {
        chain.clear();
        for (int a = int(n); a >= 0 && !done[size_t(a)]; a = nodes[size_t(a)].parent) chain.push_back(size_t(a));
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const int p = nodes[*it].parent;
            world[*it] =
                p >= 0 ? world[size_t(p)] * deform::local_transform(nodes[*it]) : deform::local_transform(nodes[*it]);
            done[*it] = true;
        }
    }
    if (mesh.skinned) {
        pose.joint_matrices.resize(mesh.joints.size());
        for (size_t j = 0; j < mesh.joints.size(); ++j)
            pose.joint_matrices[j] = world[size_t(mesh.joints[j])] * mesh.inverse_bind[j];
    } else {
        pose.joint_matrices = {mesh.mesh_node >= 0 && size_t(mesh.mesh_node) < world.size()
                                   ? world[size_t(mesh.mesh_node)]
                                   : glm::mat4(1.0f)};
    }
    return pose;
}

SkinBinding bind_skin(const AnimatedMesh& mesh, const PreparedMesh& prepared)
{
    const size_t n = prepared.vertex_count(), renders = prepared.render_to_bake.size();
    if (renders != mesh.mesh.positions.size())
        throw Error(mesh.mesh.name + ": the prepared mesh has " + std::to_string(renders) +
                    " render vertices, the animated mesh " + std::to_string(mesh.mesh.positions.size()));
    // The lowest render vertex of each bake vertex: its weld target, whose position it has.
    std::vector<uint32_t> source(n, PreparedMesh::kUnused);
    for (size_t r = renders; r-- > 0;)
        if (prepared.render_to_bake[r] != PreparedMesh::kUnused) source[prepared.render_to_bake[r]] = uint32_t(r);
    SkinBinding b;
    b.joint_count = mesh.skinned ? uint32_t(mesh.joints.size()) : 1u;
    b.morph_count = uint32_t(mesh.morph_deltas.size());
    b.joint_indices.resize(n, glm::uvec4(0));
    b.joint_weights.resize(n, glm::vec4(1, 0, 0, 0));
    if (mesh.skinned)
        for (size_t v = 0; v < n; ++v) {
            b.joint_indices[v] = mesh.joint_indices[source[v]];
            b.joint_weights[v] = mesh.joint_weights[source[v]];
        }
    b.morph_deltas.resize(size_t(b.morph_count) * n);
    for (size_t k = 0; k < b.morph_count; ++k)
        for (size_t v = 0; v < n; ++v) b.morph_deltas[k * n + v] = mesh.morph_deltas[k][source[v]];
    return b;
}

}  // namespace jade
