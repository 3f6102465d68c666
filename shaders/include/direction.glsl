// direction.glsl - a unit vector as one float: its octahedral map (Cigolle et al. 2014) with 12
// bits per coordinate, stored as the integer u·4096 + v (< 2^24, so the float is exact and
// never a NaN pattern: the t_m sources are read both as float and as integer texels).
// Round-trip error ≤ ~1e-3 rad. Zero vectors decode as +z.
#ifndef JADE_DIRECTION_GLSL
#define JADE_DIRECTION_GLSL

float encode_direction(vec3 n)
{
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    if (!(l1 > 0.0)) return 2048.0 * 4096.0 + 2048.0;  // (0, 0): +z
    vec2 p = n.xy / l1;
    if (n.z < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    vec2 q = floor(clamp(p * 0.5 + 0.5, 0.0, 1.0) * 4095.0 + 0.5);
    return q.x * 4096.0 + q.y;
}

vec3 decode_direction(float e)
{
    float qx = floor(e / 4096.0);
    vec2 p = vec2(qx, e - qx * 4096.0) / 4095.0 * 2.0 - 1.0;
    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

#endif
