#version 460
#extension GL_GOOGLE_include_directive : require
// The host's own geometry in samples/embed: a square ground quad in the plane y = height,
// generated from gl_VertexIndex (two triangles, no vertex buffer).
layout(push_constant) uniform Push {
    mat4 clip_from_world;
    float half_size;  // world units
    float height;     // world units
} push;
layout(location = 0) out vec2 ground_xz;

void main()
{
    const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 xz = corners[gl_VertexIndex] * push.half_size;
    ground_xz = xz;
    gl_Position = push.clip_from_world * vec4(xz.x, push.height, xz.y, 1.0);
}
