#version 460
#extension GL_GOOGLE_include_directive : require
// Area-weighted vertex normals and vertex areas of the deformed mesh, with the definitions of
// engine/src/mesh/prepare.cpp (normals_and_areas): per vertex the sum of the adjacent
// triangles' cross products (b − a) × (c − a) (from deform_triangles.comp), normalised; the area a third of each adjacent
// triangle's; where the sum cancels, the largest adjacent triangle's normal (the first one in
// triangle order on ties), and (0,0,1) if that is degenerate too. Each vertex gathers over its
// own adjacency list (built once on the host, triangles in ascending order), so no atomics.
#include "common.glsl"

#include "deform_interface.h"  // struct NormalsPush, shared with engine/src/deform
layout(push_constant, scalar) uniform Push { NormalsPush pc; };

layout(binding = 0, scalar) readonly buffer Triangles { vec4 triangles[]; };  // xyz: cross product, w: area
layout(binding = 1, scalar) readonly buffer AdjacencyOffsets { uint adjacency_offsets[]; };  // vertex_count + 1
layout(binding = 2, scalar) readonly buffer AdjacentTriangles { uint adjacent_triangles[]; };
layout(binding = 3, scalar) writeonly buffer Normals { vec3 normals[]; };
layout(binding = 4, scalar) writeonly buffer Areas { float areas[]; };

// prepare.cpp uses 1e-9 in float64; float32 cross products of the same triangle seen from
// different corners differ by ~1e-7 relative, so a float32 residue below 1e-5 is cancellation.
const float kCancelled = 1e-5;

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count) return;
    vec3 sum = vec3(0.0), largest_normal = vec3(0.0);
    float area = 0.0, largest = 0.0;
    uint end = adjacency_offsets[v + 1u];
    for (uint k = adjacency_offsets[v]; k < end; ++k) {
        vec4 triangle = triangles[adjacent_triangles[k]];
        vec3 cr = triangle.xyz;
        float tri_area = triangle.w;
        sum += cr;
        area += tri_area / 3.0;
        if (tri_area > largest) {
            largest = tri_area;
            largest_normal = cr;
        }
    }
    vec3 normal = sum;
    if (!(length(normal) > kCancelled * 6.0 * area)) normal = largest_normal;
    float len = length(normal);
    normals[v] = len > 0.0 && !isinf(len) ? normal / len : vec3(0.0, 0.0, 1.0);
    areas[v] = area;
}
