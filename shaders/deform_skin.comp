#version 460
#extension GL_GOOGLE_include_directive : require
// glTF morph targets and linear blend skinning (jade/deform.hpp Pose): per bake vertex
//   m = rest + Σ_k weight_k · Δ_k,   p = Σ_{i<4} w_i · joint_matrix[j_i] · m.
// The joint matrices and morph weights are evaluated on the host for the frame.
#include "common.glsl"

#include "deform_interface.h"  // struct SkinPush, shared with engine/src/deform
layout(push_constant, scalar) uniform Push { SkinPush pc; };

layout(binding = 0, scalar) readonly buffer Rest { vec3 rest[]; };
layout(binding = 1, scalar) readonly buffer MorphDeltas { vec3 morph_deltas[]; };  // [target * n + vertex]
layout(binding = 2, scalar) readonly buffer MorphWeights { float morph_weights[]; };
layout(binding = 3, scalar) readonly buffer Joints { uvec4 joints[]; };
layout(binding = 4, scalar) readonly buffer Weights { vec4 weights[]; };
layout(binding = 5, scalar) readonly buffer JointMatrices { mat4 joint_matrices[]; };
layout(binding = 6, scalar) writeonly buffer Deformed { vec3 deformed[]; };

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.vertex_count) return;
    vec3 m = rest[i];
    for (uint k = 0u; k < pc.morph_count; ++k) m += morph_weights[k] * morph_deltas[k * pc.vertex_count + i];
    uvec4 j = min(joints[i], uvec4(pc.joint_count - 1u));  // indices were checked on the host
    vec4 w = weights[i];
    vec4 p = vec4(m, 1.0);
    vec4 skinned = w.x * (joint_matrices[j.x] * p) + w.y * (joint_matrices[j.y] * p) +
                   w.z * (joint_matrices[j.z] * p) + w.w * (joint_matrices[j.w] * p);
    deformed[i] = skinned.xyz;
}
