// common.glsl - what every Jade compute shader shares.
#ifndef JADE_COMMON_GLSL
#define JADE_COMMON_GLSL

#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require

// Specialisation constant 0 is the group size, set by gpu::Kernel (see gpu/kernel.hpp).
layout(local_size_x_id = 0) in;

// Linear thread index over the 2-D grid gpu::Kernel::dispatch uses past 65,535 groups.
uint jade_thread_index()
{
    return gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
}

#include "pi.glsl"  // JADE_PI

#endif
