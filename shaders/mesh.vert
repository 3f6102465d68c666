#version 460
#extension GL_GOOGLE_include_directive : require
// mesh.vert - passes the world-space attributes through, and evaluates what of the shading is
// smooth over the surface and per vertex in nature: each transmitting light's forward lobe
// (transmission.glsl), on a fine mesh its path through the object, and the blur's variance t, once
// per vertex instead of once per fragment.
#include "shading.glsl"
#include "transmission.glsl"
#include "filament.glsl"

layout(constant_id = 0) const uint MODE = JADE_MODE_TM;  // as mesh.frag; kInputs and above: the inputs pass

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
layout(location = 4) out float out_thickness;  // mesh units; the Filament mode: its thickness in [0, 1]
// Per transmitting light: its forward lobe (transmitter_lobe).
layout(location = 5) out float out_lobe[kMaxTransmitters];
layout(location = 9) out vec3 out_scattering_normal;
layout(location = 10) out vec3 out_normal_spread;
layout(location = 11) out vec3 out_variance;  // the tm mode's t per channel (variance)
// Per transmitting light: its path t (transmitter_path) where PATH_PER_VERTEX.
layout(location = 12) out float out_path[kMaxTransmitters];
// The transmitting lights' diffused light (diffused_light), summed: smooth over the diffusion length.
layout(location = 16) out vec3 out_diffused;

void main()
{
    out_position = in_position;
    out_normal = in_normal;
    out_tm = in_tm;
    out_curvature = in_curvature;
    // The Filament mode reads its own thickness in [0, 1] here (filament.glsl).
    out_thickness = MODE == kFilament ? filament_thickness(in_thickness) : in_thickness;
    out_scattering_normal = in_scattering_normal;
    out_normal_spread = in_normal_spread;
    out_variance = MODE == kTm ? variance(in_tm, in_normal_spread) : vec3(0.0);
    vec3 v = normalize(frame.eye - in_position);
    for (uint k = 0; k < kMaxTransmitters; ++k) out_lobe[k] = k < TRANSMISSION ? transmitter_lobe(k, in_position, v) : 0.0;
    // The gather's spiral turned per vertex (the golden-ratio sequence of its index: stable while
    // the mesh deforms), so that where a tap crosses an edge of the light's view it does so at a
    // different place for each vertex: fine grain, smoothed by the interpolation, instead of
    // patches where every vertex's tap crosses the same edge together.
    float turn = 6.28318531 * fract(float(gl_VertexIndex) * 0.61803399);
    bool gather = (MODE == kTm || MODE == kInputs + 6u) && data.dipole_albedo.w > 0.0;
    out_diffused = vec3(0.0);
    // Each transmitting light's path to this vertex, read once for its path t and its gather.
    for (uint k = 0; k < kMaxTransmitters; ++k) {
        float along = k < TRANSMISSION && (PATH_PER_VERTEX == 1u || gather) ? transmitter_light_path(k, in_position) : 0.0;
        out_path[k] = PATH_PER_VERTEX == 1u && k < TRANSMISSION ? transmitter_path(in_thickness, along) : 0.0;
        if (gather && k < TRANSMISSION) out_diffused += diffused_light(k, in_position, in_normal, turn, along);
    }
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
