// jade/camera.hpp - the pinhole camera of the renderer (jade/render.hpp) and the scene renderer.
// Right-handed, in mesh units.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace jade {

/// A pinhole camera. Right-handed; looks from `eye` at `target`; `up` need not be orthogonal
/// to the view direction but not parallel to it. Near and far planes are fitted to the mesh's
/// bounding sphere unless both are given (0 < near_plane < far_plane), e.g. to share a depth
/// buffer with a host renderer (then use view_projection() for the host's own geometry).
struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 30.0f;                ///< vertical field of view, (0, 180)
    float near_plane = 0.0f, far_plane = 0.0f;  ///< mesh units; 0, 0: fitted to the mesh

    /// The clip-from-world matrix the renderer uses with explicit planes: perspectiveRH_ZO
    /// (depth 0 at near, 1 at far) with y flipped (Vulkan framebuffer rows top to bottom) times
    /// lookAtRH(eye, target, up). Throws jade::Error unless 0 < near_plane < far_plane, aspect > 0.
    glm::mat4 view_projection(float aspect) const;

    /// The camera looking at the centre of the box [lo, hi] from `direction` (from the target
    /// towards the eye), at the distance where the box's bounding sphere fills the smaller of
    /// the two fields of view with a 5 % margin.
    static Camera framing(glm::vec3 lo, glm::vec3 hi, float aspect = 1.0f, glm::vec3 direction = {0.0f, 0.0f, 1.0f},
                          glm::vec3 up = {0.0f, 1.0f, 0.0f}, float fov_y_degrees = 30.0f);
};

}  // namespace jade
