// shading/frame.hpp - the per-draw checks and constants of jade::Renderer that need none of its
// state: the settings and lights validated, the push constants with near and far fitted to the
// mesh's bounds, the material's part of the frame constants, the dynamic-rendering begin on a
// RenderTarget, and the half floats of the read-back decoded.
#pragma once

#include "shading/mesh_pipeline.hpp"

#include <jade/render.hpp>

#include <cstdint>
#include <span>

namespace jade::gpu {
class Context;
}

namespace jade::shading {

/// Throws jade::Error naming the setting: size outside 1..16384, unknown mode, more than
/// kMaxLights lights, a non-finite light or a zero direction, an unsupported sample count.
void check_settings(const gpu::Context& ctx, const RenderSettings& s, std::span<const Light> lights);

/// View-projection, eye and light count; near and far hug the bounding sphere of [bbox_min,
/// bbox_max] unless the camera gives both. Throws jade::Error for a degenerate camera.
FramePush frame_push(const Camera& cam, glm::vec3 bbox_min, glm::vec3 bbox_max, uint32_t width, uint32_t height,
                     uint32_t light_count);

/// The t_m mode's shadow filter (shadow.glsl soft_shadow_visibility), FrameData::soft_shadow,
/// soft_shadow_taps and soft_shadow_weights: the material's Burley shape per channel
/// (burley_shapes: its d, or the Burley d of the same median radius); the widest of them sampled
/// at the radii of its exact inverse CDF at (i + ½)/JADE_SOFT_SHADOW_TAPS, tap i at i times the
/// golden angle, its offset and radius in median radii; each tap weighing R_c(r)/pdf(r) per
/// channel (the Burley profile of the channel's shape over the sampled one's), normalised per
/// channel. An opaque material, or one without a profile, gets equal weights on a uniform disk
/// and median 0. The shader widens any kernel whose median radius is under a texel of the light's
/// tile to a texel.
struct SoftShadowKernel {
    float median = 0.0f;
    glm::vec4 taps[JADE_SOFT_SHADOW_TAPS]{};
    glm::vec4 weights[JADE_SOFT_SHADOW_TAPS]{};
};
SoftShadowKernel soft_shadow_kernel(const Material& m);

/// Throws jade::Error naming the material: a negative or non-finite strength, ior ≤ 0, a
/// negative roughness or specular weight.
void check_material(const Material& m);

/// The material's part of FrameData (albedo, strength, specular, transmission); the rest is zero.
FrameData material_constants(const Material& m);

/// Throws jade::Error unless the target's size and views match the settings (resolve view
/// exactly when multisampled).
void check_target(const RenderTarget& t, const RenderSettings& s);

/// vkCmdBeginRendering on the target: colour (resolved when t.resolve) and depth, cleared to the
/// background unless t.load, stored as t.keep and t.load ask; `second`: a second colour
/// attachment (the Separable mode's irradiance target).
void begin_rendering(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s,
                     const VkRenderingAttachmentInfo* second = nullptr);

/// The camera with near and far hugging the sphere about [lo, hi] (radius half the diagonal, 1 %
/// margin) unless it gives both; when the eye is inside the sphere, near is 1e-4 of far (D32
/// keeps enough precision there).
Camera fit_depth_range(const Camera& camera, glm::vec3 lo, glm::vec3 hi);

/// IEEE half to float (inf, NaN, subnormals included).
float half_to_float(uint16_t h);

}  // namespace jade::shading
