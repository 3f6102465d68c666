#version 460
#extension GL_GOOGLE_include_directive : require
// A grey checkerboard of unit squares: visibly the host's shading, not Jade's.
layout(location = 0) in vec2 ground_xz;
layout(location = 0) out vec4 color;

void main()
{
    ivec2 cell = ivec2(floor(ground_xz * 2.0));
    float c = ((cell.x + cell.y) & 1) == 0 ? 0.35 : 0.18;
    color = vec4(c, c, c, 1.0);
}
