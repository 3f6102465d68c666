// jade/deform.hpp - meshes that move: procedural deformers and glTF skins / morph targets,
// evaluated on the GPU on the bake vertices of a PreparedMesh, followed by the recomputation of
// area-weighted vertex normals and vertex areas from the deformed positions.
//
// Split of the work: what is per frame and tiny (a deformer's parameters at time t, animation
// sampling, joint matrices, morph weights) is computed on the CPU; what is per vertex (moving
// the vertices, normals and areas) runs in compute shaders (shaders/deform_*.comp).
//
// Units: positions and lengths in mesh units, angles in radians, time in seconds.
// The deformed normals and areas follow jade::prepare_mesh's definitions exactly (area-weighted
// sum of the triangles' cross products, a third of each adjacent triangle's area, the largest
// adjacent triangle's normal where the sum cancels), in float32 instead of float64.
#pragma once

#include <jade/mesh.hpp>
#include <jade/noncopyable.hpp>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace jade {

class Context;

// ------------------------------------------------------------------- procedural deformers --

enum class DeformerKind : uint32_t { Bend = 0, Twist = 1, Squash = 2, Wave = 3 };

/// A procedural deformation along a chosen axis, driven by a time t (seconds).
///
/// Frame: a = the unit vector of `axis`, u and v the next two axes cyclically (axis y: u = z,
/// v = x). A point p has height h = (p − origin)·a (0 at the base, `length` at the top) and
/// offsets y_u = (p − origin)·u, y_v = (p − origin)·v from the axis line through `origin`.
/// With s(t) = sin(2π t / period):
///   Bend    the axis line is bent into a circular arc in the (a, v) plane, its length kept:
///           curvature κ = amplitude·s(t)/length (amplitude = total bend angle at the top, rad).
///           θ = κh; h' = h·sinc θ − y_v sin θ; y_v' = h·sin(θ/2)·sinc(θ/2) + y_v cos θ
///           (= the exact arc, written without 1/κ so that κ = 0 is the identity).
///   Twist   rotation about the axis line by φ = amplitude·s(t)·h/length (amplitude = the
///           angle at the top, rad), counter-clockwise seen from +a.
///   Squash  volume-preserving squash and stretch: scale σ = 1 + amplitude·s(t) along a from
///           the base, 1/√σ across the axis line (det = 1). amplitude < 1 (unitless).
///   Wave    a travelling wave across the axis: y_v' = y_v + amplitude·sin(2π(h/wavelength −
///           t/period)) (amplitude, wavelength in mesh units).
struct ProceduralDeformer {
    DeformerKind kind = DeformerKind::Bend;
    uint32_t axis = 1;        ///< 0 = x, 1 = y, 2 = z
    glm::vec3 origin{0.0f};   ///< a point of the axis line at the base, mesh units
    float length = 1.0f;      ///< extent along the axis, mesh units (> 0)
    float amplitude = 0.5f;   ///< see above: rad (bend, twist), unitless (squash), mesh units (wave)
    float wavelength = 1.0f;  ///< wave only, mesh units (> 0)
    float period = 2.0f;      ///< seconds per cycle (> 0)

    /// A deformer fitted to a mesh's bounds: origin at the centre of the base of the box along
    /// `axis`, length = the box's extent; amplitudes that look good: bend 0.8 rad, twist 1.2 rad,
    /// squash 0.25, wave 4 % of the length with a wavelength of half the length.
    static ProceduralDeformer fit(DeformerKind kind, const PreparedMesh& mesh, uint32_t axis = 1);
};

// ------------------------------------------------------------------ glTF skins, animations --

enum class Interpolation : uint32_t { Linear, Step, CubicSpline };
enum class AnimationPath : uint32_t { Translation, Rotation, Scale, Weights };

/// One glTF animation channel with its sampler. `values` is flat: `width` floats per element
/// (3 translation/scale, 4 rotation as x,y,z,w, the morph-target count for weights); with
/// CubicSpline, three elements per key (in-tangent, value, out-tangent), as in glTF.
struct AnimationChannel {
    int node = 0;
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    uint32_t width = 3;
    std::vector<float> times;  ///< seconds, strictly increasing
    std::vector<float> values;
};

struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels;
    double duration() const;  ///< the last key time over all channels, seconds
};

/// A glTF node: local TRS (a node given by a matrix is not animatable and keeps `matrix`).
struct AnimatedNode {
    int parent = -1;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    bool has_matrix = false;
    glm::mat4 matrix{1.0f};
};

/// One animated mesh of a glTF file (see jade/io.hpp load_animated_gltf): the bind pose and
/// what moves it. Per-render-vertex data is indexed like mesh.positions.
struct AnimatedMesh {
    TriangleMesh mesh;                                 ///< bind pose, the mesh's own coordinates
    int mesh_node = -1;                                ///< the node that instances the mesh
    std::vector<std::vector<glm::vec3>> morph_deltas;  ///< [target][render vertex], mesh units
    std::vector<float> default_weights;                ///< one per morph target
    bool skinned = false;
    std::vector<int> joints;                ///< skin joints (node indices)
    std::vector<glm::mat4> inverse_bind;    ///< one per joint
    std::vector<glm::uvec4> joint_indices;  ///< per render vertex, into `joints`
    std::vector<glm::vec4> joint_weights;   ///< per render vertex
    std::vector<AnimatedNode> nodes;        ///< the whole node hierarchy, in file order
    std::vector<Animation> animations;
};

/// What the GPU needs for one frame. Vertex p (after morphing: p + Σ_k weights[k]·Δ_k) goes to
/// Σ_i w_i · joint_matrices[j_i] · p. A mesh without a skin has one "joint": the world matrix
/// of its node, with weight 1.
struct Pose {
    std::vector<glm::mat4> joint_matrices;
    std::vector<float> morph_weights;
};

/// Samples `animation` (index into mesh.animations; none if mesh has none) at time t seconds
/// and evaluates the node hierarchy: joint matrix = world(joint) · inverse_bind (glTF skinning;
/// the mesh node's own transform is ignored for skinned meshes, as the spec says). A channel at
/// time t (clamped to the first and last key): LINEAR interpolates component-wise, rotations by
/// slerp (shortest arc); STEP holds the key at or before t; CUBICSPLINE is glTF's cubic Hermite
/// with tangents scaled by the key interval (rotations are normalised afterwards). A node's local
/// transform is `matrix` when it has one, else translation · rotation · scale.
Pose evaluate_pose(const AnimatedMesh& mesh, size_t animation, double t);

/// Per-bake-vertex skin and morph data. Each bake vertex takes the attributes of the lowest
/// numbered render vertex welded into it (the one whose position it has).
struct SkinBinding {
    uint32_t joint_count = 1;
    uint32_t morph_count = 0;
    std::vector<glm::uvec4> joint_indices;  ///< per bake vertex
    std::vector<glm::vec4> joint_weights;   ///< per bake vertex
    std::vector<glm::vec3> morph_deltas;    ///< [target * vertex_count + vertex]
};
SkinBinding bind_skin(const AnimatedMesh& mesh, const PreparedMesh& prepared);

// ------------------------------------------------------------------------------ the GPU side --

/// GPU time of the stages of one deform() call, milliseconds.
struct DeformTimings {
    double deform_ms = 0, normals_ms = 0, wall_ms = 0;
};

/// The deformed bake vertices, read back.
struct DeformedVertices {
    std::vector<glm::vec3> positions, normals;
    std::vector<float> areas;
};

/// Owns the GPU buffers of one mesh's deformation: rest positions, the triangles and each
/// vertex's adjacent triangles (built once on the CPU), the deformed positions, normals and
/// areas. Create one per mesh and Context; not thread-safe; destroy before the Context.
class MeshDeformer : NonCopyable {
public:
    MeshDeformer(Context& context, const PreparedMesh& rest);
    ~MeshDeformer();

    /// Uploads skin and morph data (from bind_skin on the same PreparedMesh).
    void set_skin(const SkinBinding& binding);

    /// Deforms the rest positions at time t, then recomputes normals and areas; waits.
    DeformTimings deform(const ProceduralDeformer& deformer, double t);
    /// Morphs and skins the rest positions with `pose` (needs set_skin), then normals; waits.
    DeformTimings deform(const Pose& pose);

    /// The same passes recorded into the caller's command buffer (for a frame that goes on to
    /// re-bake and draw from the buffers below without waiting). Records the deform pass, a
    /// compute barrier, the normals pass and a full compute barrier; the caller adds barriers
    /// for other stages. record(Pose) writes the joint matrices and morph weights into
    /// host-visible buffers at once: the previous submission that read them must have completed.
    void record(VkCommandBuffer cmd, const ProceduralDeformer& deformer, double t);
    void record(VkCommandBuffer cmd, const Pose& pose);

    DeformedVertices read() const;

    /// The GPU buffers, for passes that consume the deformed mesh without a read-back (e.g.
    /// DynamicBake::record, Renderer::record_vertex_update). Layout: tightly packed float[3] per
    /// bake vertex (positions, normals), float (areas).
    struct Buffers {
        VkBuffer positions, normals, areas;
        size_t vertex_count;
    };
    Buffers buffers() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// A PreparedMesh for the deformed surface: `rest`'s triangles and render-vertex map with the
/// deformed positions, normals and areas, and bounds recomputed from the positions.
PreparedMesh deformed_mesh(const PreparedMesh& rest, DeformedVertices deformed);

}  // namespace jade
