// lut_interface.h - what the translucency LUT's builder (shading/lut.cpp, lut_build.comp) and
// its float64 reference (shading/lut_reference.cpp) share, written once for C++ and GLSL.
#ifndef JADE_LUT_INTERFACE_H
#define JADE_LUT_INTERFACE_H

// Both sum the Fourier series of the circular convolution for t ≥ this (rad²), and integrate
// directly below it, where the series would need many terms.
#define JADE_LUT_SERIES_FROM_T 0.1

#ifdef __cplusplus
#include <cstdint>

namespace jade::shading {
namespace glsl {
using uint = std::uint32_t;
}  // namespace glsl
using namespace glsl;  // only this name: the struct below is written in GLSL's words
#endif

// lut_build.comp's push constants: the LUT's size and the variance of its last row.
struct LutBuildPush {
    uint width;
    uint height;
    float t_max;
};

#ifdef __cplusplus
static_assert(sizeof(LutBuildPush) == 12);
}  // namespace jade::shading
#endif

#endif  // JADE_LUT_INTERFACE_H
