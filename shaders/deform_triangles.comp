#version 460
#extension GL_GOOGLE_include_directive : require
// First half of the normals pass: per deformed triangle its cross product (b − a) × (c − a)
// (twice its vector area, as prepare.cpp computes it, once per triangle) and its area. The
// second half (deform_normals.comp) gathers them per vertex.
#include "common.glsl"

#include "deform_interface.h"  // struct TrianglesPush, shared with engine/src/deform
layout(push_constant, scalar) uniform Push { TrianglesPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Indices { uint indices[]; };
layout(binding = 2, scalar) writeonly buffer Triangles { vec4 triangles[]; };  // xyz: cross product, w: area

void main()
{
    uint t = jade_thread_index();
    if (t >= pc.triangle_count) return;
    vec3 a = positions[indices[3u * t]], b = positions[indices[3u * t + 1u]], c = positions[indices[3u * t + 2u]];
    vec3 cr = cross(b - a, c - a);
    triangles[t] = vec4(cr, 0.5 * length(cr));
}
