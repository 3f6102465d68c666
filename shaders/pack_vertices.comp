#version 460
#extension GL_GOOGLE_include_directive : require
// pack_vertices.comp - a deforming mesh's new positions, normals and t_m (float3 streams per
// bake vertex, e.g. a MeshDeformer's and a DynamicBake's buffers) copied into the renderer's
// interleaved vertex buffer (and the thickness, when given), on the GPU: no mesh data goes through the host per frame. The
// curvature (fourth attribute) stays the one set_mesh computed. Layout: renderer.cpp's Vertex.
#include "common.glsl"

layout(push_constant, scalar) uniform Push { uint vertex_count; uint has_thickness; } pc;

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Normals { vec3 normals[]; };
layout(binding = 2, scalar) readonly buffer Tm { vec3 tm[]; };
struct Vertex {
    vec3 position;
    vec3 normal;
    vec3 tm;
    float curvature;
    float thickness;
};
layout(binding = 3, scalar) buffer Vertices { Vertex vertices[]; };
layout(binding = 4, scalar) readonly buffer Thickness { float thickness[]; };

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.vertex_count) return;
    vertices[i].position = positions[i];
    vertices[i].normal = normals[i];
    // t_m ≥ 0 and finite, as set_mesh requires of host data (a NaN would poison the LUT rows).
    vec3 t = tm[i];
    vertices[i].tm = clamp(mix(t, vec3(0.0), isnan(t)), vec3(0.0), vec3(3.0e38));
    if (pc.has_thickness != 0u) {
        float th = thickness[i];
        vertices[i].thickness = isnan(th) ? 0.0 : clamp(th, 0.0, 3.0e38);
    }
}
