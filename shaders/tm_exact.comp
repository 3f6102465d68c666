#version 460
#extension GL_GOOGLE_include_directive : require
// t_m by brute force over all vertex pairs: the GPU ground truth. Sources are staged through
// shared memory one tile at a time (on lavapipe loads cost far more than arithmetic), each
// tile is summed plainly and tiles are added with compensated summation, which keeps the
// float32 error near 1e-6 relative even for 10^6 sources.
#include "common.glsl"
#include "tm_common.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
} pc;

layout(binding = 1, scalar) readonly buffer Sources { vec4 sources[]; };  // xyz position, w area
layout(binding = 2, scalar) readonly buffer Visibility { float visibility[]; };  // 1 − A_o
layout(binding = 3, scalar) writeonly buffer Tm { vec3 tm[]; };

const uint TILE = 64u;  // = the group size the host sets (gpu::KernelDesc::local_size)
shared vec4 tile_source[TILE];
shared float tile_visibility[TILE];

void main()
{
    uint i = jade_thread_index();
    bool in_range = i < pc.vertex_count;
    vec3 x = in_range ? sources[i].xyz : vec3(0.0);
    vec3 sum = vec3(0.0), comp = vec3(0.0);

    for (uint base = 0u; base < pc.vertex_count; base += TILE) {
        uint j = base + gl_LocalInvocationIndex;
        barrier();
        tile_source[gl_LocalInvocationIndex] = j < pc.vertex_count ? sources[j] : vec4(0.0);
        tile_visibility[gl_LocalInvocationIndex] = j < pc.vertex_count ? visibility[j] : 0.0;
        barrier();
        if (!in_range) continue;
        vec3 tile_sum = vec3(0.0);
        uint n = min(TILE, pc.vertex_count - base);
        for (uint k = 0u; k < n; ++k) {
            float vis = tile_visibility[k];
            if (vis == 0.0) continue;
            vec4 s = tile_source[k];
            float rho = sqrt(s.w / JADE_PI);
            float r = distance(x, s.xyz);
            bool self = base + k == i;
            for (uint c = 0u; c < CHANNELS; ++c)
                tile_sum[c] += vis * (self ? self_kernel(profiles[c], rho) : pair_kernel(profiles[c], r, s.w, rho));
        }
        compensated_add(sum, comp, tile_sum);
    }
    if (!in_range) return;
    vec3 t = sum + comp;
    tm[i] = CHANNELS == 1u ? vec3(t.x) : t;
}
