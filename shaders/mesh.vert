#version 460
#extension GL_GOOGLE_include_directive : require
// mesh.vert - passes the world-space attributes through; the shading is all per fragment.
#include "shading.glsl"

layout(location = 0) in vec3 in_position;   // mesh units
layout(location = 1) in vec3 in_normal;     // unit, outward
layout(location = 2) in vec3 in_tm;         // translucency magnitude, linear RGB, unitless
layout(location = 3) in float in_curvature; // signed mean curvature, 1/mesh units
layout(location = 4) in float in_thickness; // mean inward distance, mesh units
layout(location = 5) in vec3 in_scattering_normal;  // unit: what the translucent diffuse term is lit along
layout(location = 6) in vec3 in_normal_spread;      // per channel, [0, 1]

layout(location = 0) out vec3 out_position;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_tm;
layout(location = 3) out float out_curvature;
layout(location = 4) out float out_thickness;
layout(location = 5) out vec3 out_scattering_normal;
layout(location = 6) out vec3 out_normal_spread;

void main()
{
    out_position = in_position;
    out_normal = in_normal;
    out_tm = in_tm;
    out_curvature = in_curvature;
    out_thickness = in_thickness;
    out_scattering_normal = in_scattering_normal;
    out_normal_spread = in_normal_spread;
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
