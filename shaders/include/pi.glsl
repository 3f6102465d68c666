// pi.glsl - π for every shader (compute and draw); C++ uses std::numbers::pi.
#ifndef JADE_PI_GLSL
#define JADE_PI_GLSL

const float JADE_PI = 3.14159265358979323846;

#endif
