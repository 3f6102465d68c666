#version 460
#extension GL_GOOGLE_include_directive : require
// pack_vertices.comp - a deforming mesh's new positions, normals and t_m (float3 streams per
// bake vertex, e.g. a MeshDeformer's and a DynamicBake's buffers) copied into the renderer's
// interleaved vertex buffer (and the thickness, when given), on the GPU: no mesh data goes through the host per frame. The
// curvature (fourth attribute) stays the one set_mesh computed. Layout: renderer.cpp's Vertex.
#include "common.glsl"

layout(push_constant, scalar) uniform Push { uint vertex_count; uint has_thickness; uint has_scattering_normal; } pc;

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Normals { vec3 normals[]; };
layout(binding = 2, scalar) readonly buffer Tm { vec3 tm[]; };
struct Vertex {
    vec3 position;
    vec3 normal;
    vec3 tm;
    float curvature;
    float thickness;
    vec3 scattering_normal;
    vec3 normal_spread;
};
layout(binding = 3, scalar) buffer Vertices { Vertex vertices[]; };
layout(binding = 4, scalar) readonly buffer Thickness { float thickness[]; };
// DynamicBake's per-channel normal sums N_c at 3·i + c (tm_state.glsl): the scattering normal
// is the direction of their sum (the vertex normal where it has none), the spread per channel
// 1 − |N_c|/t_m,c clamped to [0, 1] (jade/bake.hpp BakeResult).
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
    vec3 s = normals[i], spread = vec3(0.0);
    if (pc.has_scattering_normal != 0u) {
        vec3 n0 = normal_sums[3u * i], n1 = normal_sums[3u * i + 1u], n2 = normal_sums[3u * i + 2u];
        s = n0 + n1 + n2;
        vec3 len = vec3(length(n0), length(n1), length(n2));
        vec3 ratio = mix(vec3(1.0), len / max(vertices[i].tm, vec3(1e-30)), greaterThan(vertices[i].tm, vec3(0.0)));
        spread = clamp(1.0 - mix(ratio, vec3(1.0), isnan(ratio)), vec3(0.0), vec3(1.0));
    }
    float len2 = dot(s, s);
    vertices[i].scattering_normal = len2 > 1e-30 && len2 < 3e38 ? s * inversesqrt(len2) : normals[i];
    vertices[i].normal_spread = spread;
    if (pc.has_thickness != 0u) {
        float th = thickness[i];
        vertices[i].thickness = isnan(th) ? 0.0 : clamp(th, 0.0, 3.0e38);
    }
}
