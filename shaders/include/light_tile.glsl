// light_tile.glsl - where a point falls in a light's depth tile (shading/light_depth.hpp,
// LightTile in shading_interface.h): what the transmission term's light path and the shadows read.
#ifndef JADE_LIGHT_TILE_GLSL
#define JADE_LIGHT_TILE_GLSL

#include "shading.glsl"  // data

layout(binding = 3) uniform sampler2D light_depth_atlas;  // RGBA32F: the depths of 4 surfaces along each light, one tile a light

// `position` in tile t (atlas column t): xy ∈ [0, 1] over the tile, z its depth along the light in
// the units the layers are stored in (the tile's range): the clip depth of an orthographic tile,
// the distance from the light of a perspective one (after the divide by w: the clip depth is not
// linear, and differences of it would not be lengths).
vec3 light_tile_coords(uint t, vec3 position)
{
    vec4 p = data.light_tiles[t].view_proj * vec4(position, 1.0);
    vec4 origin = data.light_tiles[t].origin, depth = data.light_tiles[t].depth;
    float z = origin.w > 0.5 ? (length(position - origin.xyz) - depth.x) / depth.y : p.z;
    return vec3(p.xy / p.w * 0.5 + 0.5, z);
}

#endif
