#version 460
#extension GL_GOOGLE_include_directive : require
// Procedural deformers (jade/deform.hpp ProceduralDeformer): moves each bake vertex from its
// rest position. The host evaluates the time dependence (bend curvature, twist rate, squash
// factor, wave phase) so that this pass is a pure function of the rest position.
#include "common.glsl"

#include "deform_interface.h"  // struct ProceduralPush, shared with engine/src/deform
layout(push_constant, scalar) uniform Push { ProceduralPush pc; };

layout(binding = 0, scalar) readonly buffer Rest { vec3 rest[]; };
layout(binding = 1, scalar) writeonly buffer Deformed { vec3 deformed[]; };

// sin(x)/x, 1 at x = 0 (the series keeps float precision for small x).
float sinc(float x) { return abs(x) < 1e-3 ? 1.0 - x * x / 6.0 : sin(x) / x; }

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.vertex_count) return;
    // Local frame: h along the axis, (yu, yv) across it; u, v are the next axes cyclically.
    uint a = pc.axis, u = (pc.axis + 1u) % 3u, v = (pc.axis + 2u) % 3u;
    vec3 d = rest[i] - pc.origin;
    float h = d[a], yu = d[u], yv = d[v];
    if (pc.kind == JADE_DEFORM_BEND) {
        float theta = pc.amount * h;
        float s = sin(theta), c = cos(theta), half_theta = 0.5 * theta;
        float nh = h * sinc(theta) - yv * s;
        float nv = h * sin(half_theta) * sinc(half_theta) + yv * c;
        h = nh;
        yv = nv;
    } else if (pc.kind == JADE_DEFORM_TWIST) {
        float phi = pc.amount * h;
        float s = sin(phi), c = cos(phi);
        float nu = c * yu - s * yv;
        float nv = s * yu + c * yv;
        yu = nu;
        yv = nv;
    } else if (pc.kind == JADE_DEFORM_SQUASH) {
        float across = inversesqrt(pc.amount);
        h *= pc.amount;
        yu *= across;
        yv *= across;
    } else {
        yv += pc.amount * sin(pc.wave_k * h - pc.wave_phase);
    }
    vec3 o;
    o[a] = h;
    o[u] = yu;
    o[v] = yv;
    deformed[i] = pc.origin + o;
}
