#version 460
// fullscreen.vert - one triangle that covers the viewport (vkCmdDraw(cmd, 3, 1, 0, 0), no vertex
// buffer): the fullscreen passes of gpu/pipeline.hpp. Vertices (−1, −1), (3, −1), (−1, 3).
void main()
{
    vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
