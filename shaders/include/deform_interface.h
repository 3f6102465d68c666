// deform_interface.h - what the deformer's C++ (deform/mesh_deformer.cpp) and its compute
// shaders (deform_*.comp) must agree on, written once: their push constants and the
// procedural deformers' kinds. Scalar layout places these members where C++ does; sizes are
// checked in C++.
#ifndef JADE_DEFORM_INTERFACE_H
#define JADE_DEFORM_INTERFACE_H

// Procedural deformers: jade::DeformerKind's values (mesh_deformer.cpp asserts they match; the
// public enum cannot include this private header).
#define JADE_DEFORM_BEND 0
#define JADE_DEFORM_TWIST 1
#define JADE_DEFORM_SQUASH 2
#define JADE_DEFORM_WAVE 3

#ifdef __cplusplus
#include <glm/vec3.hpp>

#include <cstdint>

namespace jade::deform {
namespace glsl {
using uint = std::uint32_t;
using vec3 = glm::vec3;
}  // namespace glsl
using namespace glsl;  // only these names: the structs below are written in GLSL's words
#endif

// deform_procedural.comp: one procedural deformer at one time (the host evaluates the time).
struct ProceduralPush {
    uint vertex_count;
    uint kind;         // JADE_DEFORM_*
    uint axis;         // 0 x, 1 y, 2 z
    float amount;      // bend: curvature κ (1/units); twist: rad per unit; squash: σ; wave: amplitude (units)
    vec3 origin;       // base of the axis line, mesh units
    float wave_k;      // wave: 2π / wavelength (1/units)
    float wave_phase;  // wave: 2π t / period (rad)
};

// deform_skin.comp: morph targets, then linear blend skinning.
struct SkinPush {
    uint vertex_count;
    uint morph_count;
    uint joint_count;
};

// deform_triangles.comp: each triangle's cross product and area.
struct TrianglesPush {
    uint triangle_count;
};

// deform_normals.comp: each vertex's normal from its triangles.
struct NormalsPush {
    uint vertex_count;
};

#ifdef __cplusplus
static_assert(sizeof(ProceduralPush) == 36 && sizeof(SkinPush) == 12 && sizeof(TrianglesPush) == 4 &&
              sizeof(NormalsPush) == 4);
}  // namespace jade::deform
#endif

#endif  // JADE_DEFORM_INTERFACE_H
