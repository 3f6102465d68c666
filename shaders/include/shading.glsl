// shading.glsl - what mesh.vert and mesh.frag share with shading/renderer.cpp. Keep the
// layouts in step with FramePush and FrameData there (scalar block layout, all vec4s).
#ifndef JADE_SHADING_GLSL
#define JADE_SHADING_GLSL

#extension GL_EXT_scalar_block_layout : require

const float JADE_PI = 3.14159265358979323846;

layout(push_constant, scalar) uniform FramePush {
    mat4 view_proj;     // world (mesh units) to clip space, y already flipped for Vulkan
    vec3 eye;           // camera position, mesh units
    uint light_count;
} frame;

struct GpuLight {
    vec4 vector;        // xyz: towards the light (w = 0) or its position (w = 1)
    vec4 color;         // rgb: irradiance (directional) or intensity (point); w unused
};

const uint kColorMapStops = 9;

// Shading modes (specialisation constant MODE of both stages, jade::ShadingMode), and the
// inputs pass: MODE = kInputs + k writes the k-th vec4 of the rasterised shading inputs
// (Renderer::shading_inputs) instead of shading.
const uint kLambert = 0, kCurvature = 1, kTm = 2, kFalseColor = 3, kInputs = 4;

const uint kMaxLights = 64;  // renderer.cpp: kMaxLights

layout(binding = 0, scalar) uniform FrameData {
    vec4 albedo_strength;   // k_d (linear RGB), strength (variance per unit t_m)
    vec4 specular;          // F0, α = roughness², weight; Material::spread_strength (rad² per unit normal spread)
    vec4 lut_map;           // translucency LUT quads: column cos θ·x + x, x = (W−1)/2; y = W − 1 quads a row;
                            // row (t / t_max)^¼ · z, z = H − 1; w = H − 2 the last row of quads
    vec4 curvature_map;     // curvature LUT:    u = cos θ · x + y, v = s / (1 + s) · z + w
    vec4 params;            // 1 / t_max, d̄ (curvature length, mesh units), false-colour min, 1 / range
    vec4 transmission;      // σ_t (linear RGB, 1/mesh unit), weight (jade/material.hpp Transmission)
    vec4 transmission_diffusion;  // σ_tr (1/mesh unit), diffusion weight
    vec4 transmission_scatter;    // σ_s' (1/mesh unit), unused
    vec4 transmission_shape; // lobe exponent n, (n + 1)/(2π), normal_mix, 1: diffuse × boundary transmittance
    vec4 light_depth_map;   // light-depth tile size (texels), tiles in the atlas, depth range (mesh units), unused
    mat4 light_depth[4];    // world → light clip space of each transmitter's tile (shading/light_depth.hpp)
    vec4 color_map[kColorMapStops];  // false-colour stops, linear RGB
    vec4 transmission_table_map;  // 1 / step of the attenuation table (mesh units), last texel, last interval
    GpuLight transmitters[4];  // the lights drawn with transmission (transmission.glsl); color.w: depth tile, 0 none
    GpuLight lights[kMaxLights];
} data;

#endif
