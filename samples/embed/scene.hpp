// samples/embed/scene.hpp - what the host's frame shows: its size, the height of the host's
// ground and the one camera of the ground and Jade's sphere. tests/test_embed.cpp projects
// with the same camera to find the sphere, the ground and the sky in the sample's PNG.
#pragma once

#include <jade/render.hpp>

#include <cstdint>

namespace samples::embed {

constexpr uint32_t kWidth = 320, kHeight = 240;
// The ground cuts the unit sphere at the origin: its lowest cap is hidden by the depth test.
constexpr float kGroundHeight = -0.6f;

// Explicit planes make the depth buffer shared between the two draws meaningful.
inline jade::Camera camera()
{
    jade::Camera camera;
    camera.eye = {0.0f, 1.4f, 5.0f};
    camera.target = {0.0f, -0.3f, 0.0f};
    camera.fov_y_degrees = 35.0f;
    camera.near_plane = 0.1f;
    camera.far_plane = 50.0f;
    return camera;
}

}  // namespace samples::embed
