// jade/light.hpp - the lights of the renderer (jade/render.hpp) and two presets about a camera.
// Units: directional irradiance E and point intensity I (E = I / d²) are linear RGB in arbitrary
// but consistent units; positions in mesh units.
#pragma once

#include <jade/camera.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace jade {

/// A light for the lit modes (at most 64 per draw).
struct Light {
    enum class Type : uint32_t { Directional = 0, Point = 1 };
    Type type = Type::Directional;
    glm::vec3 vector{0.0f, 0.0f, 1.0f};  ///< Directional: towards the light (any length); Point: position
    glm::vec3 color{1.0f};               ///< Directional: irradiance E; Point: intensity I (E = I/d²)

    /// Shorthands: a directional light towards `towards_light` with irradiance E, a point light.
    static Light directional(glm::vec3 towards_light, glm::vec3 irradiance)
    {
        return {Type::Directional, towards_light, irradiance};
    }
    static Light point(glm::vec3 position, glm::vec3 intensity) { return {Type::Point, position, intensity}; }
};

/// A key light from the upper front-left of the camera (E = 2.5) and a dim fill from the
/// lower right (E = 0.4), both directional.
std::vector<Light> default_lights(const Camera& camera);
/// Figure 1 of the poster: a strong back light from behind the object, slightly above and to
/// the left (E = 6), a dim front key from the upper left (E = 0.6) and a faint fill (0.15):
/// with t_m shading, light from behind wraps around and thin parts such as the ears glow.
std::vector<Light> figure1_lights(const Camera& camera);

}  // namespace jade
