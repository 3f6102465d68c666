#version 460
#extension GL_GOOGLE_include_directive : require
// pack_vertices.comp - a deforming mesh's new positions, normals and t_m (float3 streams per
// bake vertex, e.g. a MeshDeformer's and a DynamicBake's buffers) copied into the renderer's
// interleaved vertex buffer (and the thickness, when given), on the GPU: no mesh data goes through the host per frame. The
// curvature (fourth attribute) stays the one set_mesh computed. Layout: struct Vertex, shading_interface.h.
#include "common.glsl"
#include "shading_interface.h"  // structs Vertex and PackPush, shared with engine/src/shading
#include "scattering_normal.h"  // scattering_direction, normal_spread: the static bake's read-back calls them too

layout(push_constant, scalar) uniform Push { PackPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Normals { vec3 normals[]; };
layout(binding = 2, scalar) readonly buffer Tm { vec3 tm[]; };
layout(binding = 3, scalar) buffer Vertices { Vertex vertices[]; };
layout(binding = 4, scalar) readonly buffer Thickness { float thickness[]; };
// DynamicBake's per-channel normal sums N_c at 3·i + c (tm_state.glsl): the scattering normal
// and the spread per channel as scattering_normal.h makes them.
layout(binding = 5, scalar) readonly buffer NormalSums { vec3 normal_sums[]; };

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.vertex_count) return;
    vertices[i].position = positions[i];
    vertices[i].normal = normals[i];
    // t_m ≥ 0 and finite, as set_mesh requires of host data (a NaN would poison the LUT rows).
    vec3 t = tm[i];
    vertices[i].tm = clamp(mix(t, vec3(0.0), isnan(t)), vec3(0.0), vec3(3.0e38));
    vec3 s = scattering_direction(normals[i], vec3(0.0), vec3(0.0)), spread = vec3(0.0);
    if (pc.has_scattering_normal != 0u) {
        vec3 n0 = normal_sums[3u * i], n1 = normal_sums[3u * i + 1u], n2 = normal_sums[3u * i + 2u];
        s = scattering_direction(n0, n1, n2);
        spread = normal_spread(n0, n1, n2, vertices[i].tm);
    }
    vertices[i].scattering_normal = s == vec3(0.0) ? normals[i] : s;
    vertices[i].normal_spread = spread;
    if (pc.has_thickness != 0u) {
        float th = thickness[i];
        vertices[i].thickness = isnan(th) ? 0.0 : clamp(th, 0.0, 3.0e38);
    }
}
