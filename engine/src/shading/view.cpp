// shading/view.cpp - cameras, light presets and the names of modes and tone maps.
#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/error.hpp>
#include <jade/render.hpp>

#include <glm/geometric.hpp>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace jade {

namespace {
// Indexed by ShadingMode.
constexpr std::string_view kModeNames[] = {"lambert",  "curvature", "tm",    "tm-false-color",
                                           "filament", "separable", "burley"};
constexpr std::string_view kToneMapNames[] = {"none", "reinhard", "aces"};

// The camera's right, up and backward (towards the eye) unit vectors.
struct Frame {
    glm::vec3 right, up, back;
};
Frame camera_frame(const Camera& c)
{
    glm::vec3 back = glm::normalize(c.eye - c.target);
    glm::vec3 right = glm::normalize(glm::cross(c.up, back));
    return {right, glm::cross(back, right), back};
}
}  // namespace

std::string_view dev::shading_mode_name(ShadingMode mode)
{
    return uint32_t(mode) < std::size(kModeNames) ? kModeNames[uint32_t(mode)] : "unknown";
}

ShadingMode dev::parse_shading_mode(std::string_view name)
{
    std::string known;
    for (uint32_t i = 0; i < std::size(kModeNames); ++i) {
        if (name == kModeNames[i]) return ShadingMode(i);
        known += (known.empty() ? "" : ", ") + std::string(kModeNames[i]);
    }
    throw Error("shading mode '" + std::string(name) + "' is not one of " + known);
}

ToneMap dev::parse_tone_map(std::string_view name)
{
    for (uint32_t i = 0; i < 3; ++i)
        if (name == kToneMapNames[i]) return ToneMap(i);
    throw Error("tone map '" + std::string(name) + "' is not one of none, reinhard, aces");
}

glm::mat4 Camera::view_projection(float aspect) const
{
    if (!(near_plane > 0.0f && far_plane > near_plane) || !(aspect > 0.0f))
        throw Error("camera: view_projection needs 0 < near_plane < far_plane and aspect > 0 (near " +
                    std::to_string(near_plane) + ", far " + std::to_string(far_plane) + ", aspect " +
                    std::to_string(aspect) + ")");
    glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(fov_y_degrees), aspect, near_plane, far_plane);
    proj[1][1] *= -1.0f;  // Vulkan's framebuffer y points down: rows come out top to bottom
    return proj * glm::lookAtRH(eye, target, up);
}

Camera Camera::framing(glm::vec3 lo, glm::vec3 hi, float aspect, glm::vec3 direction, glm::vec3 up, float fov_y_degrees)
{
    if (!(aspect > 0.0f) || !(fov_y_degrees > 0.0f && fov_y_degrees < 180.0f) || !(glm::length(direction) > 0.0f))
        throw Error("Camera::framing: needs aspect > 0, a field of view in (0, 180) degrees and a direction");
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-30f);
    const float half_y = 0.5f * glm::radians(fov_y_degrees);
    const float half_x = std::atan(std::tan(half_y) * aspect);
    // The sphere fills the smaller half-angle: distance = r / sin(half angle), plus 5 %.
    const float distance = 1.05f * radius / std::sin(std::min(half_x, half_y));
    Camera c;
    c.target = centre;
    c.eye = centre + glm::normalize(direction) * distance;
    c.up = up;
    c.fov_y_degrees = fov_y_degrees;
    return c;
}

std::vector<Light> back_lights(const Camera& camera)
{
    const std::vector<Light> key = default_lights(camera), back = figure1_lights(camera);
    return {key[0], back[0]};
}

std::vector<Light> default_lights(const Camera& camera)
{
    Frame f = camera_frame(camera);
    return {Light::directional(-0.6f * f.right + 0.7f * f.up + 0.8f * f.back, glm::vec3(2.5f)),
            Light::directional(0.7f * f.right - 0.3f * f.up + 0.5f * f.back, glm::vec3(0.4f))};
}

std::vector<Light> figure1_lights(const Camera& camera)
{
    Frame f = camera_frame(camera);
    return {Light::directional(-0.3f * f.right + 0.35f * f.up - 1.0f * f.back, glm::vec3(6.0f)),
            Light::directional(-0.6f * f.right + 0.7f * f.up + 0.8f * f.back, glm::vec3(0.6f)),
            Light::directional(0.7f * f.right - 0.3f * f.up + 0.5f * f.back, glm::vec3(0.15f))};
}

}  // namespace jade
